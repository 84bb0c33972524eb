"""pvbatch under MPI: 3 points in all, on the first ranks; the filter must warn once that there are
fewer than 4 distinct points, count nothing as left out, and keep every rank's points with no cells.
Their Voronoi cells in a box, which has no tetrahedron to find a halo with, must fill it. Points
none of which is finite give no Voronoi cells, with a warning that says so.

usage: mpiexec -np N pvbatch --mpi TestMPIFewPoints.py <plugin .so>
"""
import sys

from paraview.simple import *

LoadPlugin(sys.argv[1], remote=False, ns=globals())
script = """
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkCommonCore import vtkPoints
rank = vtkMultiProcessController.GetGlobalController().GetLocalProcessId()
points = vtkPoints()
for x in [(0, 0, 0), (1, 0, 0), (0, 1, 0)][rank::2]:
    points.InsertNextPoint(x)
self.GetOutput().SetPoints(points)
"""
points = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
delaunay = FastDelaunay3D(Input=points)
delaunay.UpdatePipeline()
info = delaunay.GetDataInformation()
if info.GetNumberOfCells() != 0 or info.GetNumberOfPoints() != 3:
    sys.exit("TestMPIFewPoints: %d cells and %d points" % (info.GetNumberOfCells(), info.GetNumberOfPoints()))
print("TestMPIFewPoints: 3 points and no cells on %d ranks" % servermanager.ActiveConnection.GetNumberOfDataPartitions())

cells = servermanager.Fetch(FastVoronoi3D(Input=points, Bounds=[0, 2, 0, 2, -1, 1]))
volumes = cells.GetCellData().GetArray("Volume")
total = sum(volumes.GetValue(c) for c in range(cells.GetNumberOfCells())) if volumes else 0
if cells.GetNumberOfCells() != 3 or abs(total - 8) > 1e-12:
    sys.exit("TestMPIFewPoints: %d Voronoi cells of volume %g in a box of 8" % (cells.GetNumberOfCells(), total))
print("TestMPIFewPoints: 3 Voronoi cells fill the box")

nothing = ProgrammableSource(OutputDataSetType="vtkPolyData", Script="""
from vtkmodules.vtkCommonCore import vtkPoints
points = vtkPoints()
points.InsertNextPoint(float("nan"), 0, 0)
points.InsertNextPoint(0, float("inf"), 0)
self.GetOutput().SetPoints(points)
""")
none = FastVoronoi3D(Input=nothing)
none.UpdatePipeline()
if none.GetDataInformation().GetNumberOfCells() != 0:
    sys.exit("TestMPIFewPoints: Voronoi cells of points none of which is finite")
print("TestMPIFewPoints: no finite point, no Voronoi cells")
