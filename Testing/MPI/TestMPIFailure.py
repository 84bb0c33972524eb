"""pvbatch under MPI: rank 1 runs out of memory in the distributed filter (its address space is
capped a few megabytes above what it uses, just for that run: 8 MB runs out while the points are
spread over the ranks, 32 MB while the rank meshes). Every rank must stop (none left waiting in
a collective call for it), the output must keep every point with no cells, and the filter must run
in full once the cap is lifted. The failing rank's error is checked by the test's regular
expression.

usage: mpiexec -np N pvbatch --mpi TestMPIFailure.py <plugin .so> <megabytes>
"""
import sys

from paraview.simple import *

from mpi_cloud import uniform_cloud

LoadPlugin(sys.argv[1], remote=False, ns=globals())
count = 400000
cloud = uniform_cloud(count, 5)
# Runs on every rank before the filter and caps rank 1's address space. VTK itself aborts the
# process when one of its arrays cannot be allocated, so the cap leaves room for those.
cap = """
import resource
from vtkmodules.vtkParallelCore import vtkMultiProcessController
self.GetOutput().ShallowCopy(self.GetInput())
if vtkMultiProcessController.GetGlobalController().GetLocalProcessId() == 1:
    hard = resource.getrlimit(resource.RLIMIT_AS)[1]
    used = int(open("/proc/self/statm").read().split()[0]) * resource.getpagesize()
    resource.setrlimit(resource.RLIMIT_AS, (%s, hard))
"""
capped = ProgrammableFilter(Input=cloud, Script=cap % ("used + (%d << 20)" % int(sys.argv[2])))
delaunay = FastDelaunay3D(Input=capped)
delaunay.UpdatePipeline()
failed = delaunay.GetDataInformation()
if failed.GetNumberOfCells() != 0 or failed.GetNumberOfPoints() != count:
    sys.exit("TestMPIFailure: the failed run left %d cells and %d points of %d"
             % (failed.GetNumberOfCells(), failed.GetNumberOfPoints(), count))
capped.Script = cap % "hard"
delaunay.UpdatePipeline()
full = delaunay.GetDataInformation()
if full.GetNumberOfCells() < 6 * count or full.GetNumberOfPoints() < count:
    sys.exit("TestMPIFailure: the run after the failure gave %d cells and %d points"
             % (full.GetNumberOfCells(), full.GetNumberOfPoints()))
print("TestMPIFailure: OK on %d ranks, %d cells once memory was back"
      % (servermanager.ActiveConnection.GetNumberOfDataPartitions(), full.GetNumberOfCells()))
