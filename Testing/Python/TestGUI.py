"""Run inside the ParaView GUI: paraview --script=TestGUI.py --exit, with PV_PLUGIN_PATH set so the
plugin autoloads. Checks the filter's menu category, that every property has documentation, and a
run in the GUI's own pipeline; prints "TestGUI: OK" (the test's pass expression)."""
from paraview.simple import *
from paraview import servermanager

prototype = servermanager.ProxyManager().GetPrototypeProxy("filters", "FastDelaunay3D")
assert prototype is not None, "plugin not loaded"
hints = prototype.GetHints()
menu = hints.FindNestedElementByName("ShowInMenu")
assert menu is not None and menu.GetAttribute("category") == "Delaunay"

delaunay = FastDelaunay3D(Input=Sphere(ThetaResolution=40, PhiResolution=40))
assert delaunay.Tolerance == 0.0, "the default keeps every distinct point"
for name in delaunay.ListProperties():
    documentation = delaunay.GetProperty(name).SMProperty.GetDocumentation()
    assert documentation is not None and documentation.GetDescription().strip(), name
assert "tetrahedralization" in prototype.GetDocumentation().GetDescription()

view = GetActiveViewOrCreate("RenderView")
display = Show(delaunay, view)
Render(view)
assert delaunay.GetDataInformation().GetNumberOfCells() > 0
delaunay.Alpha = 0.1
delaunay.UpdatePipeline()
assert delaunay.GetDataInformation().GetNumberOfCells() > 0
print("TestGUI: OK")
