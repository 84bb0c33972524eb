"""pvbatch under MPI: 3 points in all, on the first ranks; the filter must warn once that there are
fewer than 4 distinct points, count nothing as left out, and keep every rank's points with no cells.

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
delaunay = FastDelaunay3D(Input=ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script))
delaunay.UpdatePipeline()
info = delaunay.GetDataInformation()
if info.GetNumberOfCells() != 0 or info.GetNumberOfPoints() != 3:
    sys.exit("TestMPIFewPoints: %d cells and %d points" % (info.GetNumberOfCells(), info.GetNumberOfPoints()))
print("TestMPIFewPoints: 3 points and no cells on %d ranks" % servermanager.ActiveConnection.GetNumberOfDataPartitions())
