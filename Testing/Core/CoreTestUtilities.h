// Helpers shared by the Core tests.
#ifndef fd3_CoreTestUtilities_h
#define fd3_CoreTestUtilities_h

#include "PointSets.h"
#include "fd3/Distributed.h"

#include <array>

namespace fd3test
{
/// Points per set in the tests that run on many threads (fewer under the thread sanitizer, which
/// is slow).
#ifdef FD3_THREAD_SANITIZER
constexpr std::size_t kThreadTestPoints = 6000;
#else
constexpr std::size_t kThreadTestPoints = 40000;
#endif

/// The exact frame of a whole point set, as a distributed run computes it from every piece.
inline fd3::Frame frameOf(const Points& p)
{
  return fd3::frameOf(p.data(), p.size() / 3);
}

/// The box {xmin, xmax, ymin, ymax, zmin, zmax}.
inline fd3::Bounds boxOf(const std::array<double, 6>& minMax)
{
  return fd3::Bounds::fromMinMax(minMax.data());
}
} // namespace fd3test

#endif
