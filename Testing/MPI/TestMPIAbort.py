"""pvbatch under MPI: rank 0 aborts the distributed filter (what ParaView's Abort button does) while
it meshes; every rank must stop (none left waiting in a collective call for it), the output must be
empty on every rank, and the filter must run in full afterwards.

usage: mpiexec -np N pvbatch --mpi TestMPIAbort.py <plugin .so> [voronoi]
voronoi: FastVoronoi3D in place of FastDelaunay3D.
"""
import sys

from paraview.simple import *

from mpi_cloud import uniform_cloud

LoadPlugin(sys.argv[1], remote=False, ns=globals())
count = 200000
cloud = uniform_cloud(count, 3)
voronoi = len(sys.argv) > 2 and sys.argv[2] == "voronoi"
delaunay = FastVoronoi3D(Input=cloud) if voronoi else FastDelaunay3D(Input=cloud)
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
filter = delaunay.GetClientSideObject()  # rank 0's
progress = []


def abort(caller, event):
    progress.append(caller.GetProgress())
    if 0 < caller.GetProgress() < 1:  # the kernel's, while it meshes
        caller.SetAbortExecute(1)


observer = filter.AddObserver("ProgressEvent", abort)
delaunay.UpdatePipeline()
aborted = delaunay.GetDataInformation()
if not any(0 < p < 1 for p in progress):
    sys.exit("TestMPIAbort: the kernel reported no progress to abort at")
if aborted.GetNumberOfCells() != 0 or aborted.GetNumberOfPoints() != 0:
    sys.exit("TestMPIAbort: an aborted run left %d cells and %d points"
             % (aborted.GetNumberOfCells(), aborted.GetNumberOfPoints()))
filter.RemoveObserver(observer)
filter.SetAbortExecute(0)
delaunay.MarkModified(delaunay)  # Apply again: only the rank that aborted would run, unless all do
delaunay.UpdatePipeline()
full = delaunay.GetDataInformation()
if full.GetNumberOfCells() < (count if voronoi else 6 * count) or full.GetNumberOfPoints() < count:
    sys.exit("TestMPIAbort: the run after the abort gave %d cells and %d points"
             % (full.GetNumberOfCells(), full.GetNumberOfPoints()))
print("TestMPIAbort: OK on %d ranks, %d cells after the aborted run" % (ranks, full.GetNumberOfCells()))
