/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "FilterBox.h"

#include "vtkAlgorithm.h"

#include <cmath>
#include <sstream>
#include <string>

namespace fd3vtk
{

fd3::Bounds BoxInUse(
  vtkAlgorithm* filter, bool useInputBounds, const double bounds[6], const fd3::Bounds& inputBounds)
{
  if (useInputBounds)
  {
    return inputBounds;
  }
  const fd3::Bounds given = fd3::Bounds::fromMinMax(bounds);
  if (!given.finite())
  {
    vtkWarningWithObjectMacro(filter,
      "Bounds (" << bounds[0] << ", " << bounds[1] << ", " << bounds[2] << ", " << bounds[3] << ", "
                 << bounds[4] << ", " << bounds[5]
                 << ") is no box (a minimum above its maximum, or a bound not finite): the "
                    "input's bounds are used");
    return inputBounds;
  }
  return given;
}

bool AnyPeriodic(const int periodic[3])
{
  return periodic[0] || periodic[1] || periodic[2];
}

fd3::PeriodicBox PeriodicBoxOf(const fd3::Bounds& box, const int periodic[3])
{
  fd3::PeriodicBox periodicBox;
  for (int a = 0; a < 3; ++a)
  {
    periodicBox.lo[a] = box.lo[a];
    periodicBox.hi[a] = box.hi[a];
    periodicBox.periodic[a] = periodic[a] != 0;
  }
  return periodicBox;
}

std::string PeriodicBoxProblem(const fd3::PeriodicBox& box)
{
  for (int a = 0; a < 3; ++a)
  {
    const double period = box.hi[a] - box.lo[a];
    if (box.periodic[a] && !(period > 0 && std::isfinite(period)))
    {
      std::ostringstream problem;
      problem << "the periodic box is [" << box.lo[a] << ", " << box.hi[a] << ") on axis "
              << "xyz"[a] << ", no period (set Bounds, with UseInputBounds off, to the box)";
      return problem.str();
    }
  }
  return std::string();
}

} // namespace fd3vtk
