"""pvpython: the proxy's default properties keep every point of a dense cloud, and a Tolerance
that skips points reports them in the field data (the warning's text is checked in TestFilter).

A dense cloud is one whose nearest neighbours are far closer than 0.001 of its bounding-box
diagonal, as in LiDAR tiles and scans: 20 tight clusters of 1,000 points (spread 1e-3) in a unit
cube, plus 2,000 points spread over the cube.

usage: pvpython TestDefaults.py <plugin .so>
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
rng = np.random.default_rng(5)
centres = rng.random((20, 3))
clustered = np.repeat(centres, 1000, axis=0) + 1e-3 * (rng.random((20000, 3)) - 0.5)
xyz = np.vstack([rng.random((2000, 3)), clustered])
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
self.GetPolyDataOutput().SetPoints(points)
"""
total = 22000


def used_points(proxy):
    output = servermanager.Fetch(proxy)
    ids = vtk_to_numpy(output.GetCells().GetConnectivityArray())
    return len(set(ids.tolist())), output


delaunay = FastDelaunay3D(Input=cloud)
assert delaunay.Tolerance == 0.0, delaunay.Tolerance
used, output = used_points(delaunay)
assert used == total, "defaults left out %d points" % (total - used)
assert output.GetFieldData().GetNumberOfArrays() == 0  # nothing left out, nothing to report

delaunay.Tolerance = 0.001  # Delaunay 3D's displayed default, applied
used, output = used_points(delaunay)
skipped = output.GetFieldData().GetArray("NumberOfSkippedPoints").GetValue(0)
assert skipped == total - used and skipped > total / 2, (skipped, used)

print("TestDefaults: %d of %d points kept by default, %d skipped at Tolerance 0.001: OK"
      % (total, total, skipped))
