"""pvpython: Fast Delaunay 3D and Fast Voronoi 3D on weighted points. Weights defaults to None,
even where the input has active scalars; a radii array then gives the regular tetrahedralization,
whose hidden points stay in the output on no cell and are counted in the field data, Alpha the
weighted alpha shape, and Fast Voronoi 3D the power cells, a hidden point's empty.

usage: pvpython TestWeighted.py <plugin .so>
"""
import sys

from paraview.simple import *
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(sys.argv[1], remote=False, ns=globals())

cloud = ProgrammableSource(OutputDataSetType="vtkPolyData")
cloud.Script = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
rng = np.random.default_rng(3)
# The corners of a box around the rest, then large balls; a small ball beside each of the first
# 500 large ones, within the hull of the others.
corners = np.array([[x, y, z] for x in (-0.1, 1.1) for y in (-0.1, 1.1) for z in (-0.1, 1.1)])
large = np.vstack([corners, rng.random((1992, 3))])
small = large[8:508] + 0.001
xyz = np.vstack([large, small])
radius = np.concatenate([rng.uniform(0.04, 0.06, 2000), np.full(500, 0.002)])
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
output = self.GetPolyDataOutput()
output.SetPoints(points)
array = numpy_to_vtk(radius, deep=True)
array.SetName("Radius")
output.GetPointData().SetScalars(array)
"""
total = 2500


def run(proxy):
    output = servermanager.Fetch(proxy)
    ids = vtk_to_numpy(output.GetCells().GetConnectivityArray())
    return output, set(ids.tolist())


cloud.UpdatePipeline()  # the domain then lists Radius, the active scalars: still not the default
delaunay = FastDelaunay3D(Input=cloud)
assert list(delaunay.Weights) == ["POINTS", "None"], delaunay.Weights
assert delaunay.WeightsAreRadii == 1
output, used = run(delaunay)
assert len(used) == total, len(used)  # unweighted: every point a vertex

delaunay.Weights = ["POINTS", "Radius"]
output, used = run(delaunay)
assert output.GetNumberOfPoints() == total
assert output.GetPointData().GetArray("Radius") is not None
hidden = int(output.GetFieldData().GetArray("NumberOfHiddenPoints").GetValue(0))
assert hidden >= 450 and len(used) + hidden == total, (hidden, len(used))
# Nearly every small ball beside a large one is hidden (not all: one beside a large ball that a
# third hides may keep a cell).
small_vertices = len([i for i in used if i >= 2000])
assert small_vertices < 25, small_vertices

delaunay.Alpha = 0.05
output, used = run(delaunay)
types = set(output.GetCellType(c) for c in range(output.GetNumberOfCells()))
assert 10 in types and output.GetNumberOfCells() > 0, types  # VTK_TETRA among the cells
assert len(used) <= total - hidden

# Fast Voronoi 3D: power cells, a hidden point's empty, the volumes filling the points' box.
voronoi = FastVoronoi3D(Input=cloud)
assert list(voronoi.Weights) == ["POINTS", "None"], voronoi.Weights
voronoi.Weights = ["POINTS", "Radius"]
cells = servermanager.Fetch(voronoi)
assert cells.GetNumberOfCells() == total
assert int(cells.GetFieldData().GetArray("NumberOfHiddenPoints").GetValue(0)) == hidden
volumes = vtk_to_numpy(cells.GetCellData().GetArray("Volume"))
box = 1.2 ** 3  # the corners' box
assert abs(volumes.sum() - box) < 1e-12 * box, volumes.sum()
assert (volumes == 0).sum() >= hidden

print("TestWeighted: %d of %d points hidden, weighted alpha shape of %d cells, power cells: OK"
      % (hidden, total, output.GetNumberOfCells()))
