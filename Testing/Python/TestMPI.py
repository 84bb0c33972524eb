"""pvbatch under MPI (2 ranks): the plugin loads on every rank and the filter runs on the pieces.

usage: mpiexec -np 2 pvbatch --mpi TestMPI.py <plugin .so>
"""
import sys

from paraview.simple import *

LoadPlugin(sys.argv[1], remote=False, ns=globals())
source = PointSource(NumberOfPoints=20000, Radius=1.0)
delaunay = FastDelaunay3D(Input=source)
ranks = ProcessIdScalars(Input=delaunay)
ranks.UpdatePipeline()
info = ranks.GetDataInformation()
assert info.GetNumberOfPoints() == 20000, info.GetNumberOfPoints()
assert info.GetNumberOfCells() > 5 * 20000, info.GetNumberOfCells()
print("TestMPI: OK on %d ranks" % servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions())
