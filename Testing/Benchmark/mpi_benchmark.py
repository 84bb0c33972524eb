"""The distributed filter's benchmark: time, peak memory of rank 0 and points exchanged.
(Names in this script avoid those that the programmable source defines in __main__: output, source.)

usage: mpiexec -np N pvbatch --mpi mpi_benchmark.py <plugin .so> <points> [kind] [filter]

Every rank generates its share of uniform points (kind "cube"), of uniform points with radii in
[0.001, 0.01] that weigh them ("radii", the weighted benchmark's set), of a torus surface
("torus") or of uniform points in the periodic unit box ("periodic") over the whole domain, so
that no file reading is timed; the time is the filter's update,
redistribution and exchange included: FastDelaunay3D's, or with filter "voronoi" FastVoronoi3D's
(its cells' polyhedra, in the points' bounds).
"""
import resource
import sys
import time

from paraview.simple import *

plugin, count = sys.argv[1], int(sys.argv[2])
kind = sys.argv[3] if len(sys.argv) > 3 else "cube"
voronoi = len(sys.argv) > 4 and sys.argv[4] == "voronoi"
LoadPlugin(plugin, remote=False, ns=globals())
script = """
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
c = vtkMultiProcessController.GetGlobalController()
rank, ranks = c.GetLocalProcessId(), c.GetNumberOfProcesses()
n = %d // ranks + (1 if rank < %d %% ranks else 0)
rng = np.random.default_rng(1 + rank)
if "%s" == "torus":
    u, v = rng.random(n) * 2 * np.pi, rng.random(n) * 2 * np.pi
    p = np.stack([(1 + 0.3 * np.cos(v)) * np.cos(u), (1 + 0.3 * np.cos(v)) * np.sin(u), 0.3 * np.sin(v)], 1)
else:
    p = rng.random((n, 3))
points = vtkPoints()
points.SetData(dsa.numpyTovtkDataArray(p, "Points"))
self.GetOutput().SetPoints(points)
if "%s" == "radii":
    dsa.WrapDataObject(self.GetOutput()).PointData.append(0.001 + 0.009 * rng.random(n), "Radius")
""" % (count, count, kind, kind)
weights = {"Weights": ["POINTS", "Radius"]} if kind == "radii" else {}
if kind == "periodic":
    weights = dict(Periodic=[1, 1, 1], UseInputBounds=0, Bounds=[0, 1, 0, 1, 0, 1])
cloud = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
cloud.UpdatePipeline()
if voronoi:
    cells = FastVoronoi3D(Input=cloud, **weights)
    start = time.perf_counter()
    cells.UpdatePipeline()
    seconds = time.perf_counter() - start
    info = cells.GetDataInformation()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print("mpi_benchmark: voronoi %s %d points, %d ranks: %.2f s, %d cells, rank 0 peak %.0f MB"
          % (kind, count, servermanager.ActiveConnection.GetNumberOfDataPartitions(), seconds,
             info.GetNumberOfCells(), peak))
    sys.exit(0)
delaunay = FastDelaunay3D(Input=cloud, ComputeStatistics=1, **weights)
start = time.perf_counter()
delaunay.UpdatePipeline()
seconds = time.perf_counter() - start
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
info = delaunay.GetDataInformation()
ghosts = info.GetNumberOfPoints() - count  # periodic: the image points
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
fields = info.DataInformation.GetFieldDataInformation()  # the figures, times of the slowest rank
figure = lambda name: fields.GetArrayInformation(name).GetComponentRange(0)[0]
print("mpi_benchmark: %s %d points, %d ranks: %.2f s (kernel %.2f s, output %.2f s), %d tetrahedra, %d ghost points used (%.2f%%), "
      "rank 0 peak %.0f MB (%.0f B/point of the rank's share)"
      % (kind, count, ranks, seconds, figure("KernelSeconds"), figure("OutputSeconds"), info.GetNumberOfCells(), ghosts, 100.0 * ghosts / count, peak,
         peak * 1048576 / (count / ranks)))
