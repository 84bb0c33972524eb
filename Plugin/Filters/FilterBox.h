/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// The box that both filters of FastDelaunay3D take from their Bounds, UseInputBounds and
// Periodic properties (ParaView's convention, as Resample To Image has it: the input's bounds
// unless the switch is off). Shared by the module's filters; not an API of its own.
#ifndef FilterBox_h
#define FilterBox_h

#include "FastDelaunay3DFiltersModule.h" // For export macro

#include "fd3/Bounds.h"
#include "fd3/Periodic.h"

#include <string>

class vtkAlgorithm;

namespace fd3vtk
{
/// The box in use: `inputBounds` where `useInputBounds`, else `bounds` (VTK's order). A box given
/// with a minimum above its maximum or a bound that is not a finite number is no box: `filter`
/// warns, and the input's bounds are used.
FASTDELAUNAY3DFILTERS_EXPORT fd3::Bounds BoxInUse(vtkAlgorithm* filter, bool useInputBounds,
  const double bounds[6], const fd3::Bounds& inputBounds);

/// Whether any of the three Periodic switches is on.
FASTDELAUNAY3DFILTERS_EXPORT bool AnyPeriodic(const int periodic[3]);

/// The kernel's periodic box: `box`, repeated along the axes whose switch is on.
FASTDELAUNAY3DFILTERS_EXPORT fd3::PeriodicBox PeriodicBoxOf(
  const fd3::Bounds& box, const int periodic[3]);

/// Why `box` cannot be a periodic box (a periodic axis of no length, or one whose length is no
/// finite double); empty where it can.
FASTDELAUNAY3DFILTERS_EXPORT std::string PeriodicBoxProblem(const fd3::PeriodicBox& box);
} // namespace fd3vtk

#endif
