"""Uniform random points in the unit cube, count in all, made by each MPI rank for its share
(seed + rank): a source for the distributed filter's pvbatch tests, with no file to read."""
from paraview.simple import ProgrammableSource

_SCRIPT = """
import numpy as np
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonCore import vtkPoints
c = vtkMultiProcessController.GetGlobalController()
rank, ranks = c.GetLocalProcessId(), c.GetNumberOfProcesses()
points = vtkPoints()
points.SetData(dsa.numpyTovtkDataArray(np.random.default_rng(%d + rank).random((%d // ranks, 3)), "Points"))
self.GetOutput().SetPoints(points)
"""


def uniform_cloud(count, seed):
    return ProgrammableSource(OutputDataSetType="vtkPolyData", Script=_SCRIPT % (seed, count))
