"""pvbatch under MPI: the distributed filter on points spread over the ranks in some way.

usage: mpiexec -np N pvbatch --mpi TestMPI.py <plugin .so> <output .pvtu> <kind> <distribution> [port [alpha | voronoi]]
port: connect as the client of a pvserver under MPI on this machine ("-" for none); alpha: the
filter's Alpha (default 0); voronoi: FastVoronoi3D in place of FastDelaunay3D, with every point's
coordinates as a "Position" array too (CheckDistributedVoronoi then compares the cells), again
without polyhedra (the same volumes, on vertex cells), and in a box inside the points and one
around them (the volumes fill each).

kind: cube, lattice (ties on the seams), clusters, sphere (exactly cospherical integer points),
outlier (the cube and one point at 1e100), speck (the cube centred on 0 and a cluster 1e-150
wide at 0): magnitudes that no scaled frame holds; radii: the cube with a "Radius" array made
from the coordinates, a few of them large enough to reach across the ranks' seams and hide points
there, that the filter weighs the points by; each with exact duplicates. distribution: one (every point on rank 0), scattered (each point on
a random rank), empty (rank 0 holds none), pvtp (written as a partitioned .pvtp, read back in
pieces, with single-precision points as files often have). Every point carries a "Label" made from
its coordinates. Writes the pieces to the .pvtu (CheckDistributed then compares them with the
one-process run) and prints the volume that Integrate Variables finds.
"""
import os
import sys

from paraview.simple import *

plugin, pieces_path, kind, distribution = sys.argv[1:5]
voronoi = len(sys.argv) > 6 and sys.argv[6] == "voronoi"
alpha = float(sys.argv[6]) if len(sys.argv) > 6 and not voronoi else 0.0
if len(sys.argv) > 5 and sys.argv[5] != "-":  # a client: the server may still be starting
    import time
    for attempt in range(60):
        try:
            Connect("localhost", int(sys.argv[5]))
            break
        except Exception:
            time.sleep(1)
    LoadPlugin(plugin, remote=True, ns=globals())
LoadPlugin(plugin, remote=False, ns=globals())

script = """
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonCore import vtkPoints
controller = vtkMultiProcessController.GetGlobalController()
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()
rng = np.random.default_rng(7)
kind, distribution, single = "%s", "%s", %s
if kind in ("cube", "radii"):
    p = rng.random((4000, 3))
elif kind == "lattice":
    g = np.arange(12.0)
    p = np.array(np.meshgrid(g, g, g)).reshape(3, -1).T
elif kind == "outlier":
    p = np.concatenate([rng.random((4000, 3)), [[1e100, 0.5, 0.5]]])
elif kind == "speck":
    p = np.concatenate([rng.random((4000, 3)) - 0.5, 1e-150 * rng.random((300, 3))])
elif kind == "clusters":
    centres = rng.random((6, 3))
    p = np.concatenate([c + 0.02 * rng.standard_normal((700, 3)) for c in centres])
else:  # integer points with x^2 + y^2 + z^2 = 25^2, and the centre
    r = np.arange(-25, 26)
    g = np.array(np.meshgrid(r, r, r)).reshape(3, -1).T
    p = np.concatenate([g[(g ** 2).sum(axis=1) == 625], [[0, 0, 0]]]).astype(float)
p = np.concatenate([p, p[:50]])  # exact duplicates
owner = {"one": np.zeros(len(p), int), "scattered": rng.integers(0, ranks, len(p)),
         "empty": 1 + rng.integers(0, ranks - 1, len(p))}[distribution]
mine = np.ascontiguousarray(p[owner == rank], dtype=np.float32 if single else float)
out = dsa.WrapDataObject(self.GetOutput())
points = vtkPoints()
points.SetData(dsa.numpyTovtkDataArray(mine, "Points"))
self.GetOutput().SetPoints(points)
m = mine.astype(float)
out.PointData.append(m[:, 0] / 4 + m[:, 1] / 2 + m[:, 2], "Label")  # CheckDistributed recomputes it
if kind == "radii":  # from the coordinates, so that a duplicate has its original's
    radius = 0.001 + 0.03 * ((m[:, 0] * 7919 + m[:, 1] * 104729 + m[:, 2] * 1299709) %% 1)
    radius[(m[:, 0] * 31337 %% 1) < 0.005] = 0.2
    out.PointData.append(radius, "Radius")
if %s:
    out.PointData.append(m, "Position")
""" % (kind, "scattered" if distribution == "pvtp" else distribution, distribution == "pvtp", voronoi)
cloud = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=script)
if distribution == "pvtp":
    pieces = os.path.splitext(pieces_path)[0] + "-input.pvtp"
    SaveData(pieces, proxy=cloud)
    cloud = XMLPartitionedPolydataReader(FileName=[pieces])
weights = {"Weights": ["POINTS", "Radius"], "WeightsAreRadii": 1} if kind == "radii" else {}
if voronoi:
    result = FastVoronoi3D(Input=cloud, ComputeDensity=1, GenerateFaces=1, **weights)
else:
    result = FastDelaunay3D(Input=cloud, Alpha=alpha, AlphaLines=1, AlphaVerts=1,  # every dimension
                            ComputeStatistics=1,  # all ranks' figures, as field data
                            ComputeDensity=1, **weights)
SaveData(pieces_path, proxy=result)
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
if voronoi:
    # ParaView's own volume of a polyhedron (Integrate Variables, Cell Size) is off on some convex
    # cells; CheckDistributedVoronoi sums the cells' Volume instead.
    print("TestMPI: volume - on %d ranks" % ranks)
    faces = servermanager.Fetch(result, idx=1)  # every rank's, appended
    area = faces.GetCellData().GetArray("Area")
    total = 0.0  # not sum(): paraview.simple brings a parallel one
    for f in range(faces.GetNumberOfCells()):
        total += area.GetValue(f)
    print("TestMPI: faces %d area %.17g" % (faces.GetNumberOfCells(), total))
    # Without polyhedra, each rank's cells are vertices at its own points with the same volumes.
    # Fetch() gathers an unstructured grid from rank 0 alone under pvbatch here (ParaView's own
    # Delaunay 3D too): each rank's piece is fetched in turn.
    def pieces(proxy):
        return [servermanager.Fetch(proxy, r) for r in range(ranks)]
    def volumes(proxy):
        values = []
        for cells in pieces(proxy):
            array = cells.GetCellData().GetArray("Volume")
            values += [array.GetValue(c) for c in range(array.GetNumberOfTuples())] if array else []
        return len(values), sorted(values)
    vertices = FastVoronoi3D(Input=cloud, GeneratePolyhedra=0, **weights)
    result_volumes = volumes(result)
    assert volumes(vertices) == result_volumes, "GeneratePolyhedra=0 changed the volumes"
    cells_made = result.GetDataInformation().GetNumberOfCells()
    assert result_volumes[0] == cells_made, (result_volumes[0], cells_made)
    types = set(piece.GetCellType(c) for piece in pieces(vertices) for c in range(piece.GetNumberOfCells()))
    assert types <= {1}, types  # VTK_VERTEX
    # A given box, inside the points and around them: every rank makes the far points that close
    # the cells from the box and the global bounds, and its mesh's frame holds them.
    lo_hi = servermanager.Fetch(cloud).GetBounds()
    for inner, outer in ((0.2, 0.7), (-0.5, 2.0)):
        box = []
        for a in range(3):
            extent = lo_hi[2 * a + 1] - lo_hi[2 * a]
            box += [lo_hi[2 * a] + inner * extent, lo_hi[2 * a] + outer * extent]
        clipped = FastVoronoi3D(Input=cloud, UseInputBounds=0, Bounds=box, GeneratePolyhedra=0,
                                **weights)
        box_volume = (box[1] - box[0]) * (box[3] - box[2]) * (box[5] - box[4])
        total = 0.0
        for v in volumes(clipped)[1]:
            total += v
        assert abs(total - box_volume) <= 1e-9 * box_volume, (box, total, box_volume)
        print("TestMPI: the cells in the box %s fill it" % box)
else:
    volume = IntegrateVariables(Input=result)
    volume.UpdatePipeline()
    integrated = servermanager.Fetch(volume).GetCellData().GetArray("Volume")  # none without 3D cells
    print("TestMPI: volume %.17g on %d ranks" % (integrated.GetValue(0) if integrated else 0.0, ranks))
