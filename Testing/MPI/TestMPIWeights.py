"""pvbatch under MPI: weights that cannot be used stop every rank with an error that says why, the
points kept and no cells; weights that are NaN or infinite leave their points out, counted on all
ranks.

usage: mpiexec -np N pvbatch --mpi TestMPIWeights.py <plugin .so>
Prints "TestMPIWeights: OK" at the end; the errors it provokes are matched by the test's regex.
"""
import sys

from paraview.simple import *

LoadPlugin(sys.argv[1], remote=False, ns=globals())
script = """
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
p = np.random.default_rng(40 + rank).random((500, 3))
points = vtkPoints()
points.SetData(dsa.numpyTovtkDataArray(p, "Points"))
self.GetOutput().SetPoints(points)
out = dsa.WrapDataObject(self.GetOutput())
out.PointData.append(p, "Vector")  # three components: no weights
radius = np.full(len(p), 0.01)
radius[:3] = np.nan  # three points a rank left out
if rank != 1:  # rank 1's piece lacks the array
    out.PointData.append(radius, "PartlyThere")
out.PointData.append(radius, "Radius")
"""
cloud = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
for name in ("Vector", "PartlyThere"):
    for make in (FastDelaunay3D, FastVoronoi3D):
        result = make(Input=cloud, Weights=["POINTS", name])
        result.UpdatePipeline()
        info = result.GetDataInformation()
        points = info.GetNumberOfPoints()
        if info.GetNumberOfCells() != 0 or (make is FastDelaunay3D and points != 500 * ranks):
            sys.exit("TestMPIWeights: %s on %s: %d cells and %d points"
                     % (make.__name__, name, info.GetNumberOfCells(), points))
        Delete(result)

weighted = FastDelaunay3D(Input=cloud, Weights=["POINTS", "Radius"], ComputeStatistics=1)
weighted.UpdatePipeline()
figures = servermanager.Fetch(weighted).GetFieldData()
invalid = figures.GetArray("NumberOfInvalidPoints").GetValue(0)
if invalid != 3 * ranks:
    sys.exit("TestMPIWeights: %g invalid points, %d expected" % (invalid, 3 * ranks))
print("TestMPIWeights: OK")
