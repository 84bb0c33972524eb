"""pvbatch under MPI: 3 points in all, one on each of the first ranks; the filter must warn once that there are
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
controller = vtkMultiProcessController.GetGlobalController()
rank, size = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
points = vtkPoints()
for x in [(0, 0, 0), (1, 0, 0), (0, 1, 0)][rank::size]:
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

# Fetch() gathers an unstructured grid from rank 0 alone under pvbatch: each rank's piece in turn.
voronoi = FastVoronoi3D(Input=points, UseInputBounds=0, Bounds=[0, 2, 0, 2, -1, 1])
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
count, total = 0, 0.0
for cells in (servermanager.Fetch(voronoi, r) for r in range(ranks)):
    volumes = cells.GetCellData().GetArray("Volume")  # paraview.simple's sum() is numpy's
    for c in range(cells.GetNumberOfCells()):
        count += 1
        total += volumes.GetValue(c)
if count != 3 or abs(total - 8) > 1e-12:
    sys.exit("TestMPIFewPoints: %d Voronoi cells of volume %g in a box of 8" % (count, total))
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
