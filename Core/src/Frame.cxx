// The frame: which shifts are exact, the scale into [-1, 1], whether a point set fits it, and the
// identity frame of the points that do not.
#include "Frame.h"

#include "Expansion.h"

#include <algorithm>
#include <cmath>

namespace fd3
{

void checkShifts(const double* xyz, std::size_t count, const double centre[3], bool exact[3])
{
  for (int a = 0; a < 3; ++a)
  {
    exact[a] = exact[a] && std::isfinite(centre[a]);
    for (std::size_t i = 0; i < count && exact[a]; ++i)
    {
      double difference, error;
      twoDiff(xyz[3 * i + a], centre[a], difference, error);
      exact[a] = error == 0.0 || !std::isfinite(xyz[3 * i + a]); // non-finite points are left out
    }
  }
}

// The scale brings the points into [-1, 1], so that no predicate overflows (1e300) or underflows
// (1e-300); the shift, where exact, also keeps far-from-origin clouds away from both.
Frame frameFor(const double lo[3], const double hi[3], const bool exact[3])
{
  Frame frame;
  double extent = 0;
  for (int a = 0; a < 3; ++a)
  {
    // The centre that checkShifts() was given; not finite where hi - lo exceeds DBL_MAX.
    const double centre = lo[a] + (hi[a] - lo[a]) / 2;
    frame.shift[a] = exact[a] && std::isfinite(centre) ? centre : 0.0;
    frame.lo[a] = lo[a];
    frame.hi[a] = hi[a];
    extent =
      std::max({extent, std::fabs(lo[a] - frame.shift[a]), std::fabs(hi[a] - frame.shift[a])});
  }
  int exponent = 0;
  std::frexp(extent, &exponent);
  // Up to 2^1022: a larger power of two is not a double (the extent of subnormal points).
  frame.scale =
    extent > 0 && std::isfinite(extent) ? std::ldexp(1.0, -std::max(exponent, -1022)) : 1.0;
  return frame;
}

bool fitsFrame(const Frame& frame, const double* xyz, std::size_t count)
{
  if (frame.identity)
    return true;
  // A power of two's inverse, where it is a double, undoes the scale as a division would.
  const double inverse = 1 / frame.scale;
  const bool multiply = std::isfinite(inverse);
  auto fits = [&](double x, int a) {
    const double y = toFrame(frame, x, a);
    if ((multiply ? y * inverse : y / frame.scale) + frame.shift[a] != x)
      return false;
    // Below 2^-137 a double's last bit can lie below 2^-190 (53 bits of significand).
    return std::fabs(y) >= 0x1p-137 || std::ldexp(y, 190) == std::trunc(std::ldexp(y, 190));
  };
  for (std::size_t i = 0; i < count; ++i)
    if (isFinite(xyz + 3 * i) &&
      !(fits(xyz[3 * i], 0) && fits(xyz[3 * i + 1], 1) && fits(xyz[3 * i + 2], 2)))
      return false;
  return true;
}

Frame identityFrame(const double lo[3], const double hi[3])
{
  Frame frame;
  std::copy(lo, lo + 3, frame.lo);
  std::copy(hi, hi + 3, frame.hi);
  frame.identity = true;
  return frame;
}

bool recoverable(const Frame& frame, const double* xyz, std::size_t count)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!isFinite(xyz + 3 * i))
      continue;
    for (int a = 0; a < 3; ++a)
    {
      const double x = xyz[3 * i + a];
      if (fromFrame(frame, toFrame(frame, x, a), a) != x || (x == 0 && std::signbit(x)))
        return false;
    }
  }
  return true;
}

} // namespace fd3
