"""pvpython: Fast Voronoi 3D through the plugin. The proxy's properties (a unit box given as
either filter is made is kept); one polyhedron per point of a clustered cloud, whose volumes
(Volume, summed) fill the box, as ParaView's own Integrate Variables measures them; the same
volumes on vertex cells without polyhedra; the Bounds clip; and an image regression of the
cells, shrunk and coloured by volume.

usage: pvpython TestVoronoi.py <plugin .so> -V <absolute baseline> -T <output dir>
"""
import sys

from paraview.simple import *
from paraview import smtesting
from vtkmodules.util.numpy_support import vtk_to_numpy

plugin = sys.argv[1]
sys.argv = [sys.argv[0]] + sys.argv[2:]
smtesting.ProcessCommandLineArguments()
LoadPlugin(plugin, remote=False, ns=globals())

cloud = ProgrammableSource(OutputDataSetType="vtkPolyData")
cloud.Script = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
rng = np.random.default_rng(3)
centres = rng.random((6, 3))
xyz = np.vstack([rng.random((600, 3)), np.repeat(centres, 100, axis=0) + 0.05 * rng.standard_normal((600, 3))])
xyz = np.clip(xyz, 0, 1)
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
self.GetPolyDataOutput().SetPoints(points)
"""
cloud.UpdatePipeline()  # as the GUI's Apply does: the box's domain then knows the input's bounds
voronoi = FastVoronoi3D(Input=cloud)
for name in ("UseInputBounds", "Bounds", "Periodic", "NumberOfThreads", "GeneratePolyhedra"):
    assert name in voronoi.ListProperties(), name
assert voronoi.GeneratePolyhedra == 1
assert voronoi.UseInputBounds == 1 and list(voronoi.Periodic) == [0, 0, 0]
# The panel shows the box in use: the input's bounds.
assert list(voronoi.Bounds) == list(servermanager.Fetch(cloud).GetBounds()), voronoi.Bounds
# A box given as the filter is made is kept, the unit cube too (the XML default's value would
# take the input's bounds instead), whether or not the input has run.
fresh = ProgrammableSource(OutputDataSetType="vtkPolyData", Script=cloud.Script)
for source in (fresh, cloud):
    for make in (FastVoronoi3D, FastDelaunay3D):
        unit = make(Input=source, UseInputBounds=0, Bounds=[0, 1, 0, 1, 0, 1])
        assert list(unit.Bounds) == [0, 1, 0, 1, 0, 1], (make, list(unit.Bounds))
        Delete(unit)
voronoi.UpdatePipeline()
output = servermanager.Fetch(voronoi)
assert output.GetNumberOfCells() == 1200, output.GetNumberOfCells()
types = set(output.GetCellType(c) for c in range(output.GetNumberOfCells()))
assert types == {42}, types  # VTK_POLYHEDRON
volume = vtk_to_numpy(output.GetCellData().GetArray("Volume"))
xyz_bounds = servermanager.Fetch(cloud).GetBounds()
box = (xyz_bounds[1] - xyz_bounds[0]) * (xyz_bounds[3] - xyz_bounds[2]) * (xyz_bounds[5] - xyz_bounds[4])
assert abs(volume.sum() - box) <= 1e-9 * box, (volume.sum(), box)
integrated = IntegrateVariables(Input=voronoi)
integrated.UpdatePipeline()
measured = servermanager.Fetch(integrated).GetCellData().GetArray("Volume").GetValue(0)
# Integrate Variables tetrahedralizes each polyhedron its own way (1e-5 off here): a coarser,
# independent measure.
assert abs(measured - box) <= 1e-4 * box, (measured, box)

voronoi.GeneratePolyhedra = 0
voronoi.UpdatePipeline()
vertices = servermanager.Fetch(voronoi)
assert vertices.GetNumberOfCells() == 1200, vertices.GetNumberOfCells()
types = set(vertices.GetCellType(c) for c in range(vertices.GetNumberOfCells()))
assert types == {1}, types  # VTK_VERTEX, at each generator
assert (vtk_to_numpy(vertices.GetCellData().GetArray("Volume")) == volume).all()
voronoi.GeneratePolyhedra = 1

voronoi.Bounds = [0.25, 0.75, 0.25, 0.75, 0.25, 0.75]
voronoi.UpdatePipeline()
unclipped = servermanager.Fetch(voronoi)  # Use Input Bounds is on: Bounds is not used
assert (vtk_to_numpy(unclipped.GetCellData().GetArray("Volume")) == volume).all()
voronoi.UseInputBounds = 0
voronoi.UpdatePipeline()
clipped = servermanager.Fetch(voronoi)
clipped_volume = vtk_to_numpy(clipped.GetCellData().GetArray("Volume")).sum()
assert abs(clipped_volume - 0.125) <= 1e-12, clipped_volume

voronoi.UseInputBounds = 1
shrink = Shrink(Input=voronoi, ShrinkFactor=0.8)
view = CreateRenderView()
view.ViewSize = [400, 300]
view.OrientationAxesVisibility = 0
display = Show(shrink, view)
ColorBy(display, ("CELLS", "Volume"))
display.LookupTable.RescaleTransferFunction(0.0, 0.0015)
view.CameraPosition = [2.2, -1.6, 1.9]
view.CameraFocalPoint = [0.5, 0.5, 0.5]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
Render(view)
if not smtesting.DoRegressionTesting(view.SMProxy):
    raise RuntimeError("image comparison failed")
print("TestVoronoi: OK")
