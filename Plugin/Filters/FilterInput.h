/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// What the filters of FastDelaunay3D (and their MPI subclasses) take from their input before the
// kernel runs: the points in the requested precision, their coordinates as doubles (whose finite
// ones fd3::finiteBounds() bounds), the weights of weighted points, and the threads to run on.
// Shared by the module's filters; not an API of its own.
#ifndef FilterInput_h
#define FilterInput_h

#include "FastDelaunay3DFiltersModule.h" // For export macro
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataArray;
class vtkDataSet;
class vtkPoints;

namespace fd3vtk
{
/// The input's points in `precision` (an OutputPointsPrecision; a value that is none gives floats,
/// as in vtkDelaunay3D), with room for `extra` more after them: the input's own array when nothing
/// changes (shared, same ids), else a copy.
FASTDELAUNAY3DFILTERS_EXPORT vtkSmartPointer<vtkPoints> PointsInPrecision(
  vtkDataSet* input, int precision, vtkIdType extra = 0);

/// The points' coordinates as x,y,z doubles: the array itself when it holds doubles, else `copy`,
/// filled without a virtual call per point.
FASTDELAUNAY3DFILTERS_EXPORT const double* CoordinatesAsDoubles(
  vtkPoints* points, std::vector<double>& copy);

/// Weighted points: whether the filter's input array to process 0 is named at all (where it is
/// not, vtkAlgorithm::GetInputArrayToProcess() reports an error; ParaView's "None" names no array
/// of the input, and that call then gives null).
FASTDELAUNAY3DFILTERS_EXPORT bool WeightsChosen(vtkAlgorithm* filter);

/// Weighted points: the weights of an input's `inputPoints` points from `array` (a radius r gives
/// r^2 where `radii`), `count` of them, 0 past the input's (points a filter adds). Empty, with the
/// reason in `problem`, where the array is not one component per input point.
FASTDELAUNAY3DFILTERS_EXPORT std::vector<double> PointWeights(
  vtkDataArray* array, vtkIdType inputPoints, bool radii, std::size_t count, std::string& problem);

/// Whether the filter has been asked to stop: vtkAlgorithm::CheckAbort() where VTK has it (VTK 9.3,
/// ParaView 5.11's VTK), else GetAbortExecute().
FASTDELAUNAY3DFILTERS_EXPORT bool AbortRequested(vtkAlgorithm* filter);

/// The threads a filter runs on: its NumberOfThreads, or VTK's SMP setting
/// (vtkSMPTools::GetEstimatedNumberOfThreads(), which ParaView's thread setting governs) for 0.
FASTDELAUNAY3DFILTERS_EXPORT int ThreadCount(int numberOfThreads);
} // namespace fd3vtk

#endif
