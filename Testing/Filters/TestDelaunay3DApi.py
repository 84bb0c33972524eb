"""Every public method of vtkDelaunay3D that VTK wraps in Python, called as a script written for
vtkDelaunay3D calls them; run once for vtkDelaunay3D and once for vtkFastDelaunay3D, the class
name the only change. InitPointInsertion takes a vtkPoints*& and is not wrapped, so InsertPoint,
which needs its mesh, is only looked up.

usage: python TestDelaunay3DApi.py vtkDelaunay3D | vtkFastDelaunay3D
"""
import sys

from vtkmodules.vtkCommonCore import vtkMinimalStandardRandomSequence, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPointLocator, vtkPolyData

if sys.argv[1] == "vtkFastDelaunay3D":
    from fastdelaunay3d.FastDelaunay3DFilters import vtkFastDelaunay3D as Delaunay
else:
    from vtkmodules.vtkFiltersCore import vtkDelaunay3D as Delaunay


def expect(condition, what):
    if not condition:
        sys.exit("TestDelaunay3DApi.py: FAILED: " + what)


d = Delaunay()
expect(d.IsA("vtkUnstructuredGridAlgorithm"), "IsA")
expect(Delaunay.SafeDownCast(d) is d, "SafeDownCast")
expect(d.NewInstance().GetClassName() == sys.argv[1], "NewInstance")
expect(d.GetNumberOfGenerationsFromBase("vtkAlgorithm") >= 1, "GetNumberOfGenerationsFromBase")
printed = str(d)  # PrintSelf
for field in ("Alpha:", "Tolerance:", "Offset:", "Locator:", "Output Points Precision:"):
    expect(field in printed, "PrintSelf shows " + field)

expect(d.GetAlphaMinValue() == 0 and d.GetAlphaMaxValue() >= 1e299, "Alpha's range")
d.SetAlpha(-1)
expect(d.GetAlpha() == 0, "Alpha clamped")
d.SetAlpha(0.2)
for flag in ("AlphaTets", "AlphaTris", "AlphaLines", "AlphaVerts", "BoundingTriangulation"):
    getattr(d, flag + "Off")()
    expect(getattr(d, "Get" + flag)() == 0, flag + "Off")
    getattr(d, "Set" + flag)(1)
    expect(getattr(d, "Get" + flag)() == 1, "Set" + flag)
    getattr(d, flag + "On")()
d.BoundingTriangulationOff()
expect(d.GetToleranceMinValue() == 0 and d.GetToleranceMaxValue() == 1, "Tolerance's range")
d.SetTolerance(2)
expect(d.GetTolerance() == 1, "Tolerance clamped")
d.SetTolerance(0.01)
expect(d.GetOffsetMinValue() == 2.5 and d.GetOffsetMaxValue() >= 1e299, "Offset's range")
d.SetOffset(1)
expect(d.GetOffset() == 2.5, "Offset clamped")
d.SetOutputPointsPrecision(1)
expect(d.GetOutputPointsPrecision() == 1, "OutputPointsPrecision")

expect(d.GetLocator() is None, "no locator before one is set or made")
d.CreateDefaultLocator()
expect(isinstance(d.GetLocator(), vtkPointLocator), "CreateDefaultLocator")
locator = vtkPointLocator()
d.SetLocator(locator)
before = d.GetMTime()
locator.SetTolerance(0.5)
expect(d.GetMTime() > before, "GetMTime counts the locator's")
d.SetLocator(None)
expect(callable(d.InsertPoint), "InsertPoint is wrapped")
d.EndPointInsertion()

random = vtkMinimalStandardRandomSequence()
random.SetSeed(7)
points = vtkPoints()
for i in range(300):
    xyz = []
    for k in range(3):
        random.Next()
        xyz.append(random.GetValue())
    points.InsertNextPoint(xyz)
cloud = vtkPolyData()
cloud.SetPoints(points)
d.SetInputData(cloud)
d.SetAlpha(0)
d.SetTolerance(0)
d.Update()
out = d.GetOutput()
expect(out.GetNumberOfPoints() == 300 and out.GetNumberOfCells() > 1000, "a pipeline run")
print("TestDelaunay3DApi.py: %s OK" % sys.argv[1])
