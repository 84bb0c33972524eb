# Generates Data/points.vtp (run with pvpython from the repository root): 12,000 points with an
# "Elevation" scalar, a trefoil-knot tube surface sample plus a sparse cloud around it.
# - The tube (radius 0.45) is sampled on a jittered grid of arc length x angle, so that its surface
#   points are about 0.09 apart: with Alpha 0.12 its alpha shape is the whole tube surface.
# - The ~2,000 sparse points keep 0.35 away from the tube and 0.3 from each other, so that no alpha
#   simplex of radius <= 0.12 joins them (their triangles and edges have radius >= 0.15).
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter

rng = np.random.default_rng(2026)
radius = 0.45


def knot(t):
    return np.stack([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)], -1)


# Arc-length parametrization of the knot, for an even sample along it.
fine = np.linspace(0, 2 * np.pi, 200001)
length = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(knot(fine), axis=0), axis=1))])
around = 30
along = 10000 // around
s = (np.arange(along)[:, None] + 0.5 + 0.4 * (rng.random((along, around)) - 0.5)) / along
a = 2 * np.pi * (np.arange(around)[None, :] + 0.5 + 0.4 * (rng.random((along, around)) - 0.5)) / around
t = np.interp(s.ravel() * length[-1], length, fine)
centre = knot(t)
tangent = knot(t + 1e-6) - centre
tangent /= np.linalg.norm(tangent, axis=1)[:, None]
u = np.stack([tangent[:, 1], -tangent[:, 0], np.zeros_like(t)], -1)
u /= np.linalg.norm(u, axis=1)[:, None]
v = np.cross(tangent, u)
a = a.ravel()[:, None]
tube = centre + radius * (np.cos(a) * u + np.sin(a) * v)

curve = knot(np.linspace(0, 2 * np.pi, 4000, endpoint=False))
sparse = []
while len(sparse) < 12000 - len(tube):
    p = rng.uniform([-3.5, -3.5, -1.5], [3.5, 3.5, 1.5])
    if np.min(np.sum((curve - p) ** 2, axis=1)) < (radius + 0.35) ** 2:
        continue
    if sparse and np.min(np.sum((np.array(sparse) - p) ** 2, axis=1)) < 0.3 ** 2:
        continue
    sparse.append(p)

xyz = np.vstack([tube, np.array(sparse)]).astype(np.float32)
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
elevation = numpy_to_vtk(xyz[:, 2].copy(), deep=True)
elevation.SetName("Elevation")
data = vtkPolyData()
data.SetPoints(points)
data.GetPointData().AddArray(elevation)
data.GetPointData().SetActiveScalars("Elevation")
writer = vtkXMLPolyDataWriter()
writer.SetFileName("Data/points.vtp")
writer.SetInputData(data)
writer.SetDataModeToBinary()
writer.SetCompressorTypeToZLib()
writer.Write()
