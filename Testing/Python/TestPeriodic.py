"""pvpython: a periodic simulation box through the plugin, as a molecular dynamics or cosmology
user has one: particles in a box of side 10, some of them outside it (unwrapped coordinates).
Fast Voronoi 3D's periodic cells fill the box exactly, with their densities; Fast Delaunay 3D's
periodic tetrahedra tile it, with image points that copy their input point's data and the same
periodic densities; with the particles' radii, the power cells fill the box too, the hidden
particles' empty, and the regular tetrahedra tile it without them; and an image regression of the
cells, shrunk and coloured by density.

usage: pvpython TestPeriodic.py <plugin .so> -V <absolute baseline> -T <output dir>
"""
import sys

import numpy as np
from paraview.simple import *
from paraview import smtesting
from vtkmodules.util.numpy_support import vtk_to_numpy

plugin = sys.argv[1]
sys.argv = [sys.argv[0]] + sys.argv[2:]
smtesting.ProcessCommandLineArguments()
LoadPlugin(plugin, remote=False, ns=globals())

particles = ProgrammableSource(OutputDataSetType="vtkPolyData")
particles.Script = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
rng = np.random.default_rng(7)
centres = rng.random((4, 3)) * 10
xyz = np.vstack([rng.random((700, 3)) * 10,
                 np.repeat(centres, 200, axis=0) + 0.8 * rng.standard_normal((800, 3))])
xyz[::13, 0] += 10  # unwrapped: a period away
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
output = self.GetPolyDataOutput()
output.SetPoints(points)
ids = numpy_to_vtk(np.arange(len(xyz), dtype=float), deep=True)
ids.SetName("ParticleId")
output.GetPointData().AddArray(ids)
radius = numpy_to_vtk(0.1 + 0.5 * rng.random(len(xyz)), deep=True)
radius.SetName("Radius")
output.GetPointData().AddArray(radius)
"""
count = 1500
box = [0, 10, 0, 10, 0, 10]

voronoi = FastVoronoi3D(Input=particles, Periodic=[1, 1, 1], UseInputBounds=0, Bounds=box,
                        ComputeDensity=1)
cells = servermanager.Fetch(voronoi)
assert cells.GetNumberOfCells() == count, cells.GetNumberOfCells()
volume = vtk_to_numpy(cells.GetCellData().GetArray("Volume"))
assert abs(volume.sum() - 1000) <= 1e-12 * 1000, volume.sum()
assert (vtk_to_numpy(cells.GetCellData().GetArray("NumberOfNeighbors")) >= 4).all()
generator = vtk_to_numpy(cells.GetCellData().GetArray("GeneratorId"))
cell_density = np.empty(count)
cell_density[generator] = vtk_to_numpy(cells.GetCellData().GetArray("Density"))

delaunay = FastDelaunay3D(Input=particles, Periodic=[1, 1, 1], UseInputBounds=0, Bounds=box,
                          ComputeDensity=1, ComputeVolume=1)
tets = servermanager.Fetch(delaunay)
assert tets.GetNumberOfPoints() > count
tet_volume = vtk_to_numpy(tets.GetCellData().GetArray("Volume"))
assert (tet_volume > 0).all()
assert abs(tet_volume.sum() - 1000) <= 1e-12 * 1000, tet_volume.sum()
source = vtk_to_numpy(tets.GetPointData().GetArray("SourcePointId"))
assert (vtk_to_numpy(tets.GetPointData().GetArray("ParticleId")) == source).all()
xyz = vtk_to_numpy(tets.GetPoints().GetData())
shift = (xyz - xyz[source]) / 10
assert np.allclose(shift, np.round(shift), atol=1e-12)  # images are whole periods away
point_density = vtk_to_numpy(tets.GetPointData().GetArray("Density"))
assert np.allclose(point_density[:count], cell_density, rtol=1e-9, atol=0)
assert (point_density[count:] == point_density[source[count:]]).all()

power = FastVoronoi3D(Input=particles, Periodic=[1, 1, 1], UseInputBounds=0, Bounds=box,
                      Weights=["POINTS", "Radius"])
power_cells = servermanager.Fetch(power)
hidden = int(power_cells.GetFieldData().GetArray("NumberOfHiddenPoints").GetValue(0))
assert hidden > 0, "radii this large in the clusters hide some particles"
power_volume = vtk_to_numpy(power_cells.GetCellData().GetArray("Volume"))
assert abs(power_volume.sum() - 1000) <= 1e-12 * 1000, power_volume.sum()
assert (power_volume == 0).sum() == hidden
regular = FastDelaunay3D(Input=particles, Periodic=[1, 1, 1], UseInputBounds=0, Bounds=box,
                         Weights=["POINTS", "Radius"], ComputeVolume=1)
regular_tets = servermanager.Fetch(regular)
assert int(regular_tets.GetFieldData().GetArray("NumberOfHiddenPoints").GetValue(0)) == hidden
regular_volume = vtk_to_numpy(regular_tets.GetCellData().GetArray("Volume"))
assert (regular_volume > 0).all()
assert abs(regular_volume.sum() - 1000) <= 1e-12 * 1000, regular_volume.sum()
used = np.unique(vtk_to_numpy(regular_tets.GetPointData().GetArray("SourcePointId"))[
    vtk_to_numpy(regular_tets.GetCells().GetConnectivityArray())])
assert len(used) == count - hidden, (len(used), count, hidden)

shrink = Shrink(Input=voronoi, ShrinkFactor=0.75)
outline = Outline(Input=Box(XLength=10, YLength=10, ZLength=10, Center=[5, 5, 5]))
view = CreateRenderView()
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
display = Show(shrink, view)
ColorBy(display, ("CELLS", "Density"))
display.LookupTable.ApplyPreset("Viridis (matplotlib)", True)
display.LookupTable.RescaleTransferFunction(0.0, 4.0)
Show(outline, view)
view.CameraPosition = [32, -20, 26]
view.CameraFocalPoint = [5, 5, 5]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
Render(view)
if not smtesting.DoRegressionTesting(view.SMProxy):
    raise RuntimeError("image comparison failed")
print("TestPeriodic: OK")
