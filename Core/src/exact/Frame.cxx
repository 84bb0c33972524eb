// The frame: which shifts are exact, the scale into [-1, 1], whether a point set fits it, and the
// identity frame of the points that do not.
#include "exact/Frame.h"

#include "exact/Expansion.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace fd3
{

namespace
{
// Not finite where hi - lo exceeds DBL_MAX: no shift then.
double centre(const Bounds& box, int axis)
{
  return box.lo[axis] + box.extent(axis) / 2;
}
} // namespace

void checkShifts(const double* xyz, std::size_t count, const Bounds& box, bool exact[3])
{
  for (int a = 0; a < 3; ++a)
  {
    const double shift = centre(box, a);
    exact[a] = exact[a] && std::isfinite(shift);
    for (std::size_t i = 0; i < count && exact[a]; ++i)
    {
      double difference, error;
      twoDiff(xyz[3 * i + a], shift, difference, error);
      exact[a] = error == 0.0 || !std::isfinite(xyz[3 * i + a]); // non-finite points are left out
    }
  }
}

// The scale brings the points into [-1, 1], so that no predicate overflows (1e300) or underflows
// (1e-300); the shift, where exact, also keeps far-from-origin clouds away from both.
Frame frameFor(const Bounds& box, const bool exact[3])
{
  Frame frame;
  frame.bounds = box;
  double extent = 0;
  for (int a = 0; a < 3; ++a)
  {
    frame.shift[a] = exact[a] ? centre(box, a) : 0.0; // exact only where finite
    extent = std::max(
      {extent, std::fabs(box.lo[a] - frame.shift[a]), std::fabs(box.hi[a] - frame.shift[a])});
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
  auto fits = [&frame](double x, int a) {
    const double y = toFrame(frame, x, a);
    // Below 2^-137 a double's last bit can lie below 2^-190 (53 bits of significand).
    return mapsExactly(frame, x, a) &&
      (std::fabs(y) >= 0x1p-137 || std::ldexp(y, 190) == std::trunc(std::ldexp(y, 190)));
  };
  for (std::size_t i = 0; i < count; ++i)
    if (isFinite(xyz + 3 * i) &&
      !(fits(xyz[3 * i], 0) && fits(xyz[3 * i + 1], 1) && fits(xyz[3 * i + 2], 2)))
      return false;
  return true;
}

Frame frameWithin(
  const double* xyz, std::size_t count, const Bounds& box, const Stretches& stretches)
{
  const auto everyStretch = [&](const std::function<void(std::size_t, std::size_t)>& f) {
    forStretches(stretches, count, f);
  };
  std::atomic<bool> exact[3] = {true, true, true};
  everyStretch([&](std::size_t begin, std::size_t end) {
    bool mine[3] = {true, true, true};
    checkShifts(xyz + 3 * begin, end - begin, box, mine);
    for (int a = 0; a < 3; ++a)
      if (!mine[a])
        exact[a] = false;
  });
  const bool shifts[3] = {exact[0], exact[1], exact[2]};
  const Frame frame = frameFor(box, shifts);
  std::atomic<bool> fits{true};
  everyStretch([&](std::size_t begin, std::size_t end) {
    if (!fitsFrame(frame, xyz + 3 * begin, end - begin))
      fits = false;
  });
  return fits ? frame : identityFrame(box);
}

Frame frameOf(const double* xyz, std::size_t count)
{
  return frameWithin(xyz, count, finiteBounds(xyz, count));
}

bool weightsFitFrame(const Frame& frame, const double* weights, std::size_t count)
{
  if (frame.identity)
    return true;
  const int twice = 2 * std::ilogb(frame.scale);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double mapped = std::ldexp(weights[i], twice);
    if (std::isfinite(weights[i]) &&
      (!std::isfinite(mapped) || std::ldexp(mapped, -twice) != weights[i]))
      return false;
  }
  return true;
}

Frame identityFrame(const Bounds& box)
{
  Frame frame;
  frame.bounds = box;
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
      if (!mapsExactly(frame, x, a) || (x == 0 && std::signbit(x)))
        return false;
    }
  }
  return true;
}

} // namespace fd3
