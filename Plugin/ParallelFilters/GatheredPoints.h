/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// Every rank's points and point data on the first rank, for the run that is not distributed
// (weights in a periodic box, which one process reports it cannot use): that rank then runs as
// one process on all the points. A
// private header of the ParallelFilters module.
#ifndef GatheredPoints_h
#define GatheredPoints_h

#include "vtkSmartPointer.h"

class vtkAlgorithm;
class vtkDataSet;
class vtkMultiProcessController;
class vtkPointSet;

namespace fd3vtk
{
/// A collective call: on rank 0, the points of every rank's `input` (none where it is null) with
/// the point data arrays that all of them have, rank after rank, each in its own order; null on
/// the other ranks, and on rank 0 where no rank has a point, after `filter` warns `noPoints`.
vtkSmartPointer<vtkPointSet> GatheredPoints(vtkMultiProcessController* controller,
  vtkDataSet* input, vtkAlgorithm* filter, const char* noPoints);
} // namespace fd3vtk

#endif
