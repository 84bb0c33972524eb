# Generates Data/points.vtp (run with pvpython from the repository root): 12,000 points, a
# trefoil-knot tube surface sample plus a sparse interior cloud, with a scalar.
import math, random
from vtkmodules.vtkCommonCore import vtkPoints, vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
random.seed(2026)
pts = vtkPoints(); pts.SetDataTypeToFloat()
s = vtkFloatArray(); s.SetName("Elevation")
def knot(t):
    return (math.sin(t) + 2*math.sin(2*t), math.cos(t) - 2*math.cos(2*t), -math.sin(3*t))
for i in range(10000):
    t = random.uniform(0, 2*math.pi); a = random.uniform(0, 2*math.pi)
    c = knot(t); d = knot(t + 1e-4)
    tx, ty, tz = [(d[k]-c[k]) for k in range(3)]; n = math.sqrt(tx*tx+ty*ty+tz*tz); tx, ty, tz = tx/n, ty/n, tz/n
    # a frame orthogonal to the tangent
    ux, uy, uz = ty, -tx, 0.0; m = math.hypot(ux, uy) or 1.0; ux, uy = ux/m, uy/m
    vx, vy, vz = ty*uz - tz*uy, tz*ux - tx*uz, tx*uy - ty*ux
    r = 0.45
    p = [c[0] + r*(math.cos(a)*ux + math.sin(a)*vx), c[1] + r*(math.cos(a)*uy + math.sin(a)*vy), c[2] + r*(math.cos(a)*uz + math.sin(a)*vz)]
    pts.InsertNextPoint(p); s.InsertNextValue(p[2])
for i in range(2000):
    p = [random.uniform(-3.5, 3.5), random.uniform(-3.5, 3.5), random.uniform(-1.5, 1.5)]
    pts.InsertNextPoint(p); s.InsertNextValue(p[2])
pd = vtkPolyData(); pd.SetPoints(pts); pd.GetPointData().AddArray(s); pd.GetPointData().SetActiveScalars("Elevation")
w = vtkXMLPolyDataWriter(); w.SetFileName("Data/points.vtp"); w.SetInputData(pd); w.SetDataModeToBinary(); w.SetCompressorTypeToZLib(); w.Write()
