"""pvbatch under MPI: the output's own points are the input points bit for bit, non-finite ones
included. A rank drops its copy of the points while its mesh holds them and takes them back from
the mesh's records afterwards; a rank with a -0 coordinate (which the records would give back as
+0) keeps its copy instead, as every rank does with a Tolerance above 0 (the points skipped for it
are not in the records). Both kinds of rank run here.

usage: mpiexec -np N pvbatch --mpi TestMPIPoints.py <plugin .so> [tolerance]
(Names here avoid those that the programmable source defines in __main__: output, source.)
"""
import struct
import sys

from paraview.simple import *
from vtkmodules.numpy_interface import dataset_adapter as dsa

LoadPlugin(sys.argv[1], remote=False, ns=globals())
script = """
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
rng = np.random.default_rng(3 + rank)
p = 5e5 + np.round(rng.random((2000, 3)) * 1e4) / 100  # far from the origin, on a 1 cm grid
p = np.concatenate([p, p[:5] + 0.01,  # 1 cm from a point: skipped for a Tolerance of 1e-7
                    [[np.nan, 5e5, 5e5], [5e5, np.inf, 5e5], [-np.inf, np.nan, 5e5 + rank]]])
if rank == 1:
    p = np.concatenate([p, [[-0.0, 5e5, 5e5]]])
points = vtkPoints()
points.SetData(dsa.numpyTovtkDataArray(np.ascontiguousarray(p), "Points"))
self.GetOutput().SetPoints(points)
"""
cloud = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
tolerance = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0
delaunay = FastDelaunay3D(Input=cloud, Tolerance=tolerance)
delaunay.UpdatePipeline()


def bits(points):
    """The points as tuples of their coordinates' bits (NaN equal to NaN, -0 unequal to +0)."""
    return sorted(tuple(struct.pack("<3d", *p)) for p in points.tolist())


# Each rank's own points as a point cloud: Fetch gathers the pieces of a vtkPolyData from every
# rank (of the vtkUnstructuredGrid, it gave rank 0's alone).
own_points = ProgrammableFilter(Input=delaunay, OutputDataSetType="vtkPolyData", Script="""
from vtkmodules.vtkCommonCore import vtkPoints
grid = dsa.WrapDataObject(self.GetInput())
points = vtkPoints()
if grid.GetNumberOfPoints() > 0:
    points.SetData(dsa.numpyTovtkDataArray(grid.Points[grid.PointData["vtkGhostType"] == 0], "Points"))
self.GetOutput().SetPoints(points)
""")
given = dsa.WrapDataObject(servermanager.Fetch(cloud)).Points
own = dsa.WrapDataObject(servermanager.Fetch(own_points)).Points
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
if ranks < 2:
    sys.exit("TestMPIPoints: needs 2 ranks or more")
if bits(own) != bits(given):
    sys.exit("TestMPIPoints: the output's own points (%d) are not the input's (%d)" % (len(own), len(given)))
print("TestMPIPoints: OK, %d points on %d ranks, tolerance %g" % (len(own), ranks, tolerance))
