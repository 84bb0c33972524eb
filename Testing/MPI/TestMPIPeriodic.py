"""pvbatch under MPI: a periodic box whose particles are spread over the ranks (some of them a
period outside the box). Fast Voronoi 3D's and Fast Delaunay 3D's periodic outputs equal, bit for
bit, those of the VTK classes run in this one process on all the particles, in rank order (the
order in which the first rank gathers them; each particle's "Id" travels with it).

usage: mpiexec -np N pvbatch --mpi TestMPIPeriodic.py <plugin .so>
(with the build's Python modules on PYTHONPATH, for the one-process classes)
"""
import sys

import numpy as np
from paraview.simple import *
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from fastdelaunay3d.FastDelaunay3DFilters import vtkFastDelaunay3D, vtkFastVoronoi3D

LoadPlugin(sys.argv[1], remote=False, ns=globals())
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()


def particles():
    rng = np.random.default_rng(11)
    p = rng.random((3000, 3)) * 4
    p[::17, 1] += 4  # a period outside the box
    return p


script = """
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
rng = np.random.default_rng(11)
p = rng.random((3000, 3)) * 4
p[::17, 1] += 4
points = vtkPoints()
points.SetData(dsa.numpyTovtkDataArray(np.ascontiguousarray(p[rank::ranks]), "Points"))
self.GetOutput().SetPoints(points)
dsa.WrapDataObject(self.GetOutput()).PointData.append(np.arange(3000.0)[rank::ranks], "Id")
"""
cloud = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
box = [0, 4, 0, 4, 0, 4]
settings = dict(Periodic=[1, 1, 1], UseInputBounds=0, Bounds=box, ComputeDensity=1)

# The same particles in one process, in the order the first rank gathers them.
p = particles()
order = np.concatenate([np.arange(3000)[r::ranks] for r in range(ranks)])
whole = vtkPolyData()
points = vtkPoints()
points.SetData(numpy_to_vtk(np.ascontiguousarray(p[order]), deep=True))
whole.SetPoints(points)
ids = numpy_to_vtk(order.astype(float), deep=True)
ids.SetName("Id")
whole.GetPointData().AddArray(ids)


def one_process(filter_class):
    f = filter_class()
    f.SetInputData(whole)
    f.SetPeriodic(1, 1, 1)
    f.UseInputBoundsOff()
    f.SetBounds(*box)
    f.ComputeDensityOn()
    f.Update()
    return f.GetOutput()


def pieces(proxy):
    """The first rank's piece; every other rank's is empty."""
    fetched = [servermanager.Fetch(proxy, r) for r in range(ranks)]
    for r in range(1, ranks):
        if fetched[r].GetNumberOfPoints() or fetched[r].GetNumberOfCells():
            sys.exit("TestMPIPeriodic: rank %d holds part of the output" % r)
    return fetched[0]


def same(a, b, what):
    for kind, x, y in (("cell", a.GetCellData(), b.GetCellData()),
                       ("point", a.GetPointData(), b.GetPointData())):
        for i in range(y.GetNumberOfArrays()):
            name = y.GetArrayName(i)
            if x.GetArray(name) is None or not np.array_equal(
                    vtk_to_numpy(x.GetArray(name)), vtk_to_numpy(y.GetArray(name)), equal_nan=True):
                sys.exit("TestMPIPeriodic: %s %s array %s differs from one process" % (what, kind, name))
    if not np.array_equal(vtk_to_numpy(a.GetPoints().GetData()), vtk_to_numpy(b.GetPoints().GetData())):
        sys.exit("TestMPIPeriodic: %s points differ from one process" % what)


cells = pieces(FastVoronoi3D(Input=cloud, **settings))
reference = one_process(vtkFastVoronoi3D)
if cells.GetNumberOfCells() != 3000 or reference.GetNumberOfCells() != 3000:
    sys.exit("TestMPIPeriodic: %d cells" % cells.GetNumberOfCells())
same(cells, reference, "Voronoi")
volume = vtk_to_numpy(cells.GetCellData().GetArray("Volume")).sum()
if abs(volume - 64) > 1e-12 * 64:
    sys.exit("TestMPIPeriodic: the cells' volume is %r, not the box's" % volume)
print("TestMPIPeriodic: %d periodic cells on %d ranks, as one process" % (3000, ranks))

tets = pieces(FastDelaunay3D(Input=cloud, ComputeVolume=1, **settings))
reference = one_process(vtkFastDelaunay3D)
same(tets, reference, "Delaunay")
if not np.array_equal(vtk_to_numpy(tets.GetCells().GetConnectivityArray()),
                      vtk_to_numpy(reference.GetCells().GetConnectivityArray())):
    sys.exit("TestMPIPeriodic: the tetrahedra differ from one process")
print("TestMPIPeriodic: %d periodic tetrahedra on %d ranks, as one process" % (tets.GetNumberOfCells(), ranks))
# No rank has a point: a warning on the first rank and empty outputs, on every rank alike.
nothing = ProgrammableSource(OutputDataSetType="vtkPolyData",
                             Script="self.GetOutput().SetPoints(vtk.vtkPoints())")
for make in (FastVoronoi3D, FastDelaunay3D):
    made = make(Input=nothing, **settings)
    # Not any(): once a Programmable Source has run in this process, `any` is numpy's here.
    for r in range(ranks):
        if servermanager.Fetch(made, r).GetNumberOfCells():
            sys.exit("TestMPIPeriodic: cells from no points")
print("TestMPIPeriodic: no points on any rank, no cells")
print("TestMPIPeriodic: OK")
