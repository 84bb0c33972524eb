"""pvpython: the FastDelaunay3D plugin loads, the proxy works, and its output keeps the contract.

usage: pvpython TestPlugin.py <plugin .so> <Data folder>
"""
import os
import sys

from paraview.simple import *

plugin, data = sys.argv[1:3]
LoadPlugin(plugin, remote=False, ns=globals())

reader = XMLPolyDataReader(FileName=[os.path.join(data, "points.vtp")])
delaunay = FastDelaunay3D(Input=reader)
for name in ("GridResolution", "VolumeThreshold", "InsertionOrder", "RandomSeed"):
    assert name in delaunay.ListProperties(), name
delaunay.UpdatePipeline()

info = delaunay.GetDataInformation()
assert info.GetNumberOfPoints() == 12000, info.GetNumberOfPoints()
assert info.DataInformation.GetDataSetTypeAsString() == "vtkUnstructuredGrid"
assert delaunay.PointData["Elevation"] is not None, "point data is passed through"

output = servermanager.Fetch(delaunay)
cells = output.GetNumberOfCells()
assert cells > 6 * 12000 * 0.8, cells
types = set(output.GetCellType(i) for i in range(cells))
assert types == {10}, types  # VTK_TETRA only

# Every tetrahedron positively oriented (VTK convention), in double precision: a sanity check of
# the wiring; the exact checks live in the C++ tests.
pts = output.GetPoints()
ids = output.GetCells().GetConnectivityArray()
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
negative = 0
for c in range(0, cells, 7):
    p = [pts.GetPoint(ids.GetValue(4 * c + k)) for k in range(4)]
    u, v, w = sub(p[1], p[0]), sub(p[2], p[0]), sub(p[3], p[0])
    det = (u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1] + (u[0] * v[1] - u[1] * v[0]) * w[2]
    negative += det <= 0
assert negative == 0, negative

# The same seed gives the same tetrahedra; the total volume is the hull's whatever the order.
delaunay.InsertionOrder = 2
delaunay.UpdatePipeline()
volume_random = IntegrateVariables(Input=delaunay)
volume_random.UpdatePipeline()
delaunay.InsertionOrder = 0
volume_brio = IntegrateVariables(Input=delaunay)
volume_brio.UpdatePipeline()
a = servermanager.Fetch(volume_random).GetCellData().GetArray("Volume").GetValue(0)
b = servermanager.Fetch(volume_brio).GetCellData().GetArray("Volume").GetValue(0)
assert abs(a - b) <= 1e-9 * abs(b), (a, b)
# Image data: the proxy accepts any dataset and tetrahedralizes its (implicit) points.
wavelet = Wavelet(WholeExtent=[0, 6, 0, 6, 0, 6])
image_tets = FastDelaunay3D(Input=wavelet)
image_tets.UpdatePipeline()
image_info = image_tets.GetDataInformation()
assert image_info.GetNumberOfPoints() == 7 ** 3
assert image_info.GetNumberOfCells() >= 5 * 6 ** 3  # at least 5 tetrahedra per lattice cube
assert image_tets.PointData["RTData"] is not None

print("TestPlugin: %d tetrahedra, hull volume %.6f: OK" % (cells, b))
