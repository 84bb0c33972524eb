// Helpers shared by the Core tests.
#ifndef fd3_CoreTestUtilities_h
#define fd3_CoreTestUtilities_h

#include "PointSets.h"
#include "fd3/Distributed.h"

#include <algorithm>

namespace fd3test
{
/// The exact frame of a whole point set, as a distributed run computes it from every piece.
inline fd3::Frame frameOf(const Points& p)
{
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = hi[a] = p[a];
    for (std::size_t i = a; i < p.size(); i += 3)
    {
      lo[a] = std::min(lo[a], p[i]);
      hi[a] = std::max(hi[a], p[i]);
    }
  }
  const double centre[3] = {
    lo[0] + (hi[0] - lo[0]) / 2, lo[1] + (hi[1] - lo[1]) / 2, lo[2] + (hi[2] - lo[2]) / 2};
  bool exact[3] = {true, true, true};
  fd3::checkShifts(p.data(), p.size() / 3, centre, exact);
  const fd3::Frame frame = fd3::frameFor(lo, hi, exact);
  return fd3::fitsFrame(frame, p.data(), p.size() / 3) ? frame : fd3::identityFrame(lo, hi);
}
} // namespace fd3test

#endif
