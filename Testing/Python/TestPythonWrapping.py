"""pvpython: vtkFastDelaunay3D is Python-wrapped. It works in a plain VTK pipeline, and
GetClientSideObject() returns the typed object (import the module first, see TOOLCHAIN notes).

usage: pvpython TestPythonWrapping.py <plugin .so>   (PYTHONPATH holds the build's site-packages)
"""
import sys

import fastdelaunay3d.FastDelaunay3DFilters  # before any GetClientSideObject()
from fastdelaunay3d.FastDelaunay3DFilters import vtkFastDelaunay3D
from vtkmodules.vtkFiltersSources import vtkPointSource

# A plain VTK pipeline.
source = vtkPointSource()
source.SetNumberOfPoints(2000)
source.SetRadius(1.0)
delaunay = vtkFastDelaunay3D()
delaunay.SetInputConnection(source.GetOutputPort())
delaunay.Update()
output = delaunay.GetOutput()
assert output.GetNumberOfPoints() == 2000
assert output.GetNumberOfCells() == delaunay.GetNumberOfTetrahedra() > 2000 * 5
assert delaunay.GetNumberOfInsertedPoints() == 2000
delaunay.SetAlpha(0.2)
delaunay.Update()
assert delaunay.GetOutput().GetNumberOfCells() > 0
assert "Alpha: 0.2" in str(delaunay)  # PrintSelf

# Through ParaView: the client-side object is the wrapped class, with its own methods.
from paraview.simple import LoadPlugin, PointSource  # noqa: E402
LoadPlugin(sys.argv[1], remote=False, ns=globals())  # defines FastDelaunay3D
proxy = FastDelaunay3D(Input=PointSource(NumberOfPoints=500, Radius=1.0), Alpha=0.0)
proxy.UpdatePipeline()
typed = proxy.GetClientSideObject()
assert isinstance(typed, vtkFastDelaunay3D), type(typed)
assert typed.GetNumberOfTetrahedra() == typed.GetOutput().GetNumberOfCells() > 0
print("TestPythonWrapping: OK")
