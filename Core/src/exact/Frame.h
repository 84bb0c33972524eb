// The exact change of coordinates the kernel computes in (fd3::Frame, fd3/Distributed.h), applied
// to points and boxes.
#ifndef fd3_Frame_h
#define fd3_Frame_h

#include "fd3/Bounds.h"
#include "fd3/Distributed.h"
#include "system/Stretches.h"

namespace fd3
{

inline double toFrame(const Frame& frame, double x, int axis)
{
  return (x - frame.shift[axis]) * frame.scale;
}

// Exact where toFrame() was: the scale is a power of two, and x - shift was exact.
inline double fromFrame(const Frame& frame, double y, int axis)
{
  return y / frame.scale + frame.shift[axis];
}

/// Whether x comes back from the frame as it went in: its image is exact.
inline bool mapsExactly(const Frame& frame, double x, int axis)
{
  return fromFrame(frame, toFrame(frame, x, axis), axis) == x;
}

/// The frame of `count` points whose finite ones lie within `box`, their bounds: frameOf() for a
/// caller that has the bounds already. Its passes over the points go by `stretches`, where given.
Frame frameWithin(
  const double* xyz, std::size_t count, const Bounds& box, const Stretches& stretches = nullptr);

/// Whether vertex records of `count` points in `frame` give each finite one back bit for bit: every
/// coordinate maps into the frame and back exactly (no underflow), and none is -0, which an exact
/// duplicate at +0 would come back as.
bool recoverable(const Frame& frame, const double* xyz, std::size_t count);

inline void toFrame(const Frame& frame, const double* p, double* out)
{
  for (int a = 0; a < 3; ++a)
    out[a] = toFrame(frame, p[a], a);
}

inline Bounds toFrame(const Frame& frame, const Bounds& box)
{
  Bounds out;
  toFrame(frame, box.lo, out.lo);
  toFrame(frame, box.hi, out.hi);
  return out;
}

} // namespace fd3

#endif
