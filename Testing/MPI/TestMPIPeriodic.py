"""pvbatch under MPI: periodic boxes whose particles are spread over the ranks (some of them a
period outside the box). Each rank computes the cells of its own particles and the tetrahedra
whose least vertex is one of them, from the other ranks' particles within its halo (their images
across the box included), widened where a rank finds it too narrow; with Alpha, the simplices of
the alpha shape whose least vertex is one of them, from the stars of its particles. Together the ranks' outputs
are those of the VTK classes run in this one process on all the particles in rank order (the
order of the input ids; each particle's "Id" travels with it): the same cells and tetrahedra, each
once, with the same values to 1e-12.

Cases: uniform particles in a box periodic on every axis; a cluster in a corner of a large box,
whose tetrahedra across the empty box need a wider halo; a slab periodic along x and y, these
first and last with an alpha shape too, every kind of simplex in it; a void, which only
the ranks whose particles border it widen their halo for; one finite particle
among NaNs, which leaves a rank with no point, or only NaNs; and particles with radii, some
hidden, which the first rank gathers (with its weighted alpha shape too).

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

# Each case: the particles (the same code runs in the Programmable Source on every rank), the box
# and the periodic axes.
CASES = {
    "uniform": ("p = rng.random((3000, 3)) * 4\np[::17, 1] += 4", [0, 4, 0, 4, 0, 4], [1, 1, 1]),
    "cluster": ("p = rng.random((600, 3)) + 0.5", [0, 4, 0, 4, 0, 4], [1, 1, 1]),
    "slab": ("p = rng.random((1500, 3)) * [4, 4, 1]\np[::13, 0] -= 4", [0, 4, 0, 4, 0, 1],
             [1, 1, 0]),
    # A void: the ranks whose particles border it widen their halo; on 3 ranks, the one whose
    # region holds the void within its first halo does not, and the ranks exchange unevenly.
    "void": ("p = rng.random((5000, 3)) * 4\np = p[np.linalg.norm(p - [3, 2, 2], axis=1) > 1.2]",
             [0, 4, 0, 4, 0, 4], [1, 1, 1]),
    # One finite particle among NaNs: a rank has none, or only NaNs.
    "lone": ("p = rng.random((200, 3)) * 4\np[1:] = np.nan", [0, 4, 0, 4, 0, 4], [1, 1, 1]),
    # Radii (r, a "Radius" array): power cells and the regular tetrahedralization.
    "radii": ("p = rng.random((1500, 3)) * 4\nr = rng.random(1500) * 0.3", [0, 4, 0, 4, 0, 4],
              [1, 1, 1]),
}


def particles(make):
    """The case's particles, and their radii (None without)."""
    rng = np.random.default_rng(11)
    scope = {"rng": rng, "np": np, "r": None}
    exec(make, {}, scope)
    return scope["p"], scope["r"]


SCRIPT = """
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
rng = np.random.default_rng(11)
r = None
%s
points = vtkPoints()
points.SetData(dsa.numpyTovtkDataArray(np.ascontiguousarray(p[rank::ranks]), "Points"))
self.GetOutput().SetPoints(points)
data = dsa.WrapDataObject(self.GetOutput()).PointData
data.append(np.arange(float(len(p)))[rank::ranks], "Id")
if r is not None:
    data.append(np.ascontiguousarray(r[rank::ranks]), "Radius")
"""


def one_process(filter_class, p, box, periodic, radii, **properties):
    """The filter in this process on the particles in rank order: the order of their input ids."""
    order = np.concatenate([np.arange(len(p))[r::ranks] for r in range(ranks)])
    whole = vtkPolyData()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(p[order]), deep=True))
    whole.SetPoints(points)
    for name, values in (("Id", order.astype(float)), ("Radius", radii)):
        if values is not None:
            array = numpy_to_vtk(np.ascontiguousarray(values[order] if name == "Radius" else values),
                                 deep=True)
            array.SetName(name)
            whole.GetPointData().AddArray(array)
    f = filter_class()
    if radii is not None:
        f.SetInputArrayToProcess(0, 0, 0, 0, "Radius")
    f.SetInputData(whole)
    f.SetPeriodic(*periodic)
    f.UseInputBoundsOff()
    f.SetBounds(*box)
    f.ComputeDensityOn()
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    f.Update()
    return f.GetOutput()


def pieces(proxy, spread=True):
    """Every rank's piece of the output; where `spread`, at least two of them hold cells."""
    fetched = [servermanager.Fetch(proxy, r) for r in range(ranks)]
    # Not sum() or min(): once a Programmable Source has run in this process, those are numpy's
    # here.
    if len([f for f in fetched if f.GetNumberOfCells()]) < (2 if ranks > 1 and spread else 1):
        sys.exit("TestMPIPeriodic: the cells are not spread over the ranks")
    return fetched


def cell_arrays(data):
    d = data.GetCellData()
    return {d.GetArrayName(i): vtk_to_numpy(d.GetArray(i)) for i in range(d.GetNumberOfArrays())}


def close(a, b, what):
    """Equal, and floats to 1e-12 relative: a rank sums in another order."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if a.shape != b.shape or not np.allclose(a, b, rtol=1e-12, atol=0, equal_nan=True):
        sys.exit("TestMPIPeriodic: %s differs from one process" % what)


def weights(radii):
    """The proxies' Weights property: the radii where there are some."""
    return ["POINTS", "Radius"] if radii is not None else ["POINTS", "None"]


def check_cells(case, cloud, p, radii, box, periodic):
    """Fast Voronoi 3D: each rank the cells of its own particles, as one process has them; with
    radii, the first rank every cell."""
    reference = one_process(vtkFastVoronoi3D, p, box, periodic, radii)
    cells = {}
    finite = int(np.isfinite(p).all(axis=1).sum())
    for part in pieces(FastVoronoi3D(Input=cloud, Periodic=periodic, UseInputBounds=0, Bounds=box,
                                     ComputeDensity=1, Weights=weights(radii)),
                       spread=finite > 1 and radii is None):
        for name, values in cell_arrays(part).items():
            cells.setdefault(name, []).append(values)
    cells = {name: np.concatenate(values) for name, values in cells.items()}
    mine, theirs = cells["Id"], vtk_to_numpy(reference.GetCellData().GetArray("Id"))
    if len(mine) != finite or len(np.unique(mine)) != finite:
        sys.exit("TestMPIPeriodic: %s: %d cells, not one per particle" % (case, len(mine)))
    order, reference_order = np.argsort(mine), np.argsort(theirs)
    for name, values in cell_arrays(reference).items():
        if name not in cells:
            sys.exit("TestMPIPeriodic: %s: no %s array in the ranks' cells" % (case, name))
        close(cells[name][order], values[reference_order], case + ": the cells' " + name)
    if periodic == [1, 1, 1]:
        volume, period = cells["Volume"].sum(), np.prod(np.diff(np.reshape(box, (3, 2))))
        if abs(volume - period) > 1e-12 * period:
            sys.exit("TestMPIPeriodic: %s: the cells' volume is %r, not the box's" % (case, volume))
    print("TestMPIPeriodic: %s: %d periodic cells on %d ranks, as one process" % (case, finite, ranks))


def cells_by_key(data, p, box):
    """Each cell (a tetrahedron, or a simplex of the alpha shape) keyed by its vertices' input
    points and their periods from the cell's least vertex, the same for every translate, with its
    cell values; and each point's input point and place with its density. A rank that gathered
    its points to the first one has none."""
    if data.GetNumberOfPoints() == 0:
        return {}, {}
    ids = vtk_to_numpy(data.GetPointData().GetArray("SourcePointId")).astype(int)
    xyz = vtk_to_numpy(data.GetPoints().GetData())
    lo, hi = np.reshape(box, (3, 2)).T
    in_rank_order = p[np.concatenate([np.arange(len(p))[r::ranks] for r in range(ranks)])]
    shifts = np.rint((xyz - in_rank_order[ids]) / (hi - lo)).astype(int)
    keyed = {}
    if data.GetNumberOfCells():
        offsets = vtk_to_numpy(data.GetCells().GetOffsetsArray())
        connectivity = vtk_to_numpy(data.GetCells().GetConnectivityArray())
        arrays = cell_arrays(data)
    for c in range(data.GetNumberOfCells()):
        vertices = sorted((ids[v],) + tuple(shifts[v]) for v in connectivity[offsets[c]:offsets[c + 1]])
        key = tuple((v[0],) + tuple(np.subtract(v[1:], vertices[0][1:])) for v in vertices)
        if key in keyed:
            sys.exit("TestMPIPeriodic: a cell twice")
        keyed[key] = {n: a[c] for n, a in arrays.items()}
    density = vtk_to_numpy(data.GetPointData().GetArray("Density"))
    return keyed, {(ids[i],) + tuple(xyz[i]): density[i] for i in range(len(ids))
                   if np.isfinite(xyz[i]).all()}


def check_tetrahedra(case, cloud, p, radii, box, periodic, alpha=0):
    """Fast Delaunay 3D: each periodic tetrahedron (or simplex of the alpha shape) once, on the rank
    of its least vertex; with radii, all on the first rank."""
    reference, reference_density = cells_by_key(
        one_process(vtkFastDelaunay3D, p, box, periodic, radii, Alpha=alpha), p, box)
    tets, density = {}, {}
    for part in pieces(FastDelaunay3D(Input=cloud, Periodic=periodic, UseInputBounds=0,
                                      Bounds=box, ComputeDensity=1, ComputeVolume=1, Alpha=alpha,
                                      AlphaLines=1, AlphaVerts=1,  # as the VTK class
                                      Weights=weights(radii)),
                       spread=np.isfinite(p).all(axis=1).sum() > 1 and radii is None):
        keyed, values = cells_by_key(part, p, box)
        if set(keyed) & set(tets):
            sys.exit("TestMPIPeriodic: %s: two ranks output the same cell" % case)
        tets.update(keyed)
        density.update(values)
    what = "tetrahedra" if alpha == 0 else "alpha shape's cells (Alpha %g)" % alpha
    if set(tets) != set(reference):
        sys.exit("TestMPIPeriodic: %s: the %s differ from one process (%d against %d)"
                 % (case, what, len(tets), len(reference)))
    keys = sorted(reference)
    for name in reference[keys[0]]:
        close([tets[k][name] for k in keys], [reference[k][name] for k in keys],
              "%s: the %s' %s" % (case, what, name))
    points = sorted(density)
    if set(points) - set(reference_density):
        sys.exit("TestMPIPeriodic: %s: a point that one process does not output" % case)
    close([density[v] for v in points], [reference_density[v] for v in points], case + ": Density")
    print("TestMPIPeriodic: %s: %d periodic %s on %d ranks, as one process"
          % (case, len(tets), what, ranks))


for case, (make, box, periodic) in CASES.items():
    cloud = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=SCRIPT % make)
    p, radii = particles(make)
    check_cells(case, cloud, p, radii, box, periodic)
    check_tetrahedra(case, cloud, p, radii, box, periodic)
    if case in ("uniform", "slab", "radii"):
        check_tetrahedra(case, cloud, p, radii, box, periodic, alpha=0.25)

# No rank has a point: a warning on the first rank and empty outputs, on every rank alike.
nothing = ProgrammableSource(OutputDataSetType="vtkPolyData",
                             Script="self.GetOutput().SetPoints(vtk.vtkPoints())")
for make in (FastVoronoi3D, FastDelaunay3D):
    made = make(Input=nothing, Periodic=[1, 1, 1], UseInputBounds=0, Bounds=[0, 4, 0, 4, 0, 4])
    # Not any(): once a Programmable Source has run in this process, `any` is numpy's here.
    for r in range(ranks):
        if servermanager.Fetch(made, r).GetNumberOfCells():
            sys.exit("TestMPIPeriodic: cells from no points")
print("TestMPIPeriodic: no points on any rank, no cells")
print("TestMPIPeriodic: OK")
