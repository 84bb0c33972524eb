// Small geometric helpers shared by the kernel's passes: the finiteness test and bounding boxes.
#ifndef fd3_Geometry_h
#define fd3_Geometry_h

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace fd3
{

/// An axis-aligned bounding box.
struct Box
{
  double lo[3] = {0, 0, 0};
  double hi[3] = {0, 0, 0};

  /// The box of the single point p.
  static Box around(const double* p)
  {
    Box box;
    for (int a = 0; a < 3; ++a)
      box.lo[a] = box.hi[a] = p[a];
    return box;
  }

  /// The box of the points xyz[3 * ids[i]], i < count (count > 0).
  static Box of(const double* xyz, const std::uint32_t* ids, std::size_t count)
  {
    Box box = around(xyz + 3 * std::size_t(ids[0]));
    for (std::size_t i = 1; i < count; ++i)
      box.include(xyz + 3 * std::size_t(ids[i]));
    return box;
  }

  void include(const double* p)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }

  double extent(int axis) const { return hi[axis] - lo[axis]; }
};

} // namespace fd3

#endif
