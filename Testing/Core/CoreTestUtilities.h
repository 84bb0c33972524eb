// Helpers shared by the Core tests.
#ifndef fd3_CoreTestUtilities_h
#define fd3_CoreTestUtilities_h

#include "PointSets.h"
#include "fd3/Distributed.h"

namespace fd3test
{
/// The exact frame of a whole point set, as a distributed run computes it from every piece.
inline fd3::Frame frameOf(const Points& p)
{
  return fd3::frameOf(p.data(), p.size() / 3);
}
} // namespace fd3test

#endif
