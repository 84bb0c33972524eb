"""The main job: tetrahedralize the bundled point cloud with the FastDelaunay3D plugin under
pvbatch, write the result (.vtu) and a picture of its alpha shape (.png), and print the figures.

usage: pvbatch demo.py <plugin .so> <input .vtp> <output folder>
"""
import os
import sys
import time

from paraview.simple import *

plugin, input_file, out_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
from knot_view import show_knot  # noqa: E402
os.makedirs(out_dir, exist_ok=True)

reader = XMLPolyDataReader(FileName=[input_file])
reader.UpdatePipeline()
delaunay = FastDelaunay3D(Input=reader, ComputeStatistics=1)  # default properties otherwise
start = time.perf_counter()
delaunay.UpdatePipeline()
seconds = time.perf_counter() - start

info = delaunay.GetDataInformation()
figures = servermanager.Fetch(delaunay).GetFieldData()
used = int(figures.GetArray("NumberOfInsertedPoints").GetValue(0))
stem = os.path.splitext(os.path.basename(input_file))[0]
vtu = os.path.join(out_dir, stem + ".vtu")
png = os.path.join(out_dir, stem + ".png")
SaveData(vtu, proxy=delaunay)

view = show_knot(FastDelaunay3D, reader, 800, 600)
SaveScreenshot(png, view, ImageResolution=[800, 600])

print("points:      %d (%d used as vertices)" % (info.GetNumberOfPoints(), used))
print("tetrahedra:  %d" % info.GetNumberOfCells())
print("seconds:     %.3f (FastDelaunay3D UpdatePipeline, pvbatch)" % seconds)
print("wrote:       %s, %s" % (vtu, png))
