"""The main job: tetrahedralize the bundled point cloud with the FastDelaunay3D plugin under
pvbatch, write the result (.vtu) and a picture (.png), and print the figures.

usage: pvbatch demo.py <plugin .so> <input .vtp> <output folder>
"""
import os
import sys
import time

from paraview.simple import *

plugin, input_file, out_dir = sys.argv[1:4]
LoadPlugin(plugin, remote=False, ns=globals())
os.makedirs(out_dir, exist_ok=True)

reader = XMLPolyDataReader(FileName=[input_file])
reader.UpdatePipeline()
delaunay = FastDelaunay3D(Input=reader)
start = time.perf_counter()
delaunay.UpdatePipeline()
seconds = time.perf_counter() - start

info = delaunay.GetDataInformation()
stem = os.path.splitext(os.path.basename(input_file))[0]
vtu = os.path.join(out_dir, stem + ".vtu")
png = os.path.join(out_dir, stem + ".png")
SaveData(vtu, proxy=delaunay)

view = CreateView("RenderView")
view.ViewSize = [800, 600]
view.OrientationAxesVisibility = 0
# Whole tetrahedra on one side of a plane through the cloud, shrunk so each one is seen.
clip = Clip(Input=delaunay, ClipType="Plane", Crinkleclip=1)
clip.ClipType.Origin = [0, 0, 0]
clip.ClipType.Normal = [0, 1, 0]
shrink = Shrink(Input=clip, ShrinkFactor=0.7)
display = Show(shrink, view)
ColorBy(display, ("POINTS", "Elevation"))
display.RescaleTransferFunctionToDataRange(True)
view.CameraPosition = [3, 12, 8]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
Render(view)
SaveScreenshot(png, view, ImageResolution=[800, 600])

print("points:      %d" % info.GetNumberOfPoints())
print("tetrahedra:  %d" % info.GetNumberOfCells())
print("seconds:     %.3f (FastDelaunay3D UpdatePipeline, pvbatch)" % seconds)
print("wrote:       %s, %s" % (vtu, png))
