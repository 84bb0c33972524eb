// FastDelaunay3D Core: an axis-aligned box, the one spelling of a box in the kernel's interfaces,
// and the pass that bounds the finite points of a set.
#ifndef fd3_Bounds_h
#define fd3_Bounds_h

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>

namespace fd3
{

/// An axis-aligned box: [lo[a], hi[a]] on each axis a. Empty, as it starts, when lo[a] > hi[a]
/// on some axis; include() grows it. Six doubles, lo then hi, with nothing else (MPI sends it as
/// such).
struct Bounds
{
  /// Empty. Not an aggregate: six doubles in braces would fill lo then hi, not VTK's order.
  Bounds() {}

  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  double hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};

  /// From VTK's order, {xmin, xmax, ymin, ymax, zmin, zmax}.
  static Bounds fromMinMax(const double minMax[6])
  {
    Bounds b;
    for (int a = 0; a < 3; ++a)
    {
      b.lo[a] = minMax[2 * a];
      b.hi[a] = minMax[2 * a + 1];
    }
    return b;
  }
  /// In VTK's order, {xmin, xmax, ymin, ymax, zmin, zmax}.
  void toMinMax(double minMax[6]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      minMax[2 * a] = lo[a];
      minMax[2 * a + 1] = hi[a];
    }
  }

  void include(const double* p)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  void include(const Bounds& other)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], other.lo[a]);
      hi[a] = std::max(hi[a], other.hi[a]);
    }
  }

  /// Whether it holds no point: lo > hi (or NaN) on some axis.
  bool empty() const { return !(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2]); }
  /// Whether it holds a point and every bound is finite.
  bool finite() const
  {
    return !empty() && std::isfinite(lo[0]) && std::isfinite(lo[1]) && std::isfinite(lo[2]) &&
      std::isfinite(hi[0]) && std::isfinite(hi[1]) && std::isfinite(hi[2]);
  }
  bool contains(const double* p) const
  {
    return lo[0] <= p[0] && p[0] <= hi[0] && lo[1] <= p[1] && p[1] <= hi[1] && lo[2] <= p[2] &&
      p[2] <= hi[2];
  }
  double extent(int axis) const { return hi[axis] - lo[axis]; }
  double volume() const { return empty() ? 0.0 : extent(0) * extent(1) * extent(2); }

  /// The diagonal's length, 0 for an empty box or a point, at most DBL_MAX for any finite box:
  /// from halves, so that spans beyond DBL_MAX stay finite, and scaled by the largest so that tiny
  /// ones do not underflow.
  double diagonal() const
  {
    double half[3], largest = 0;
    for (int a = 0; a < 3; ++a)
    {
      half[a] = std::max(hi[a] / 2 - lo[a] / 2, 0.0);
      largest = std::max(largest, half[a]);
    }
    if (!(largest > 0))
      return 0;
    double sum = 0;
    for (const double h : half)
      sum += (h / largest) * (h / largest);
    return std::min(2 * largest * std::sqrt(sum), DBL_MAX);
  }
};
static_assert(sizeof(Bounds) == 6 * sizeof(double), "six doubles, as MPI sends them");

/// The same six doubles.
inline bool operator==(const Bounds& a, const Bounds& b)
{
  return std::equal(a.lo, a.lo + 3, b.lo) && std::equal(a.hi, a.hi + 3, b.hi);
}

/// The box of the finite ones of `count` points (x,y,z triples): empty when none is. On `threads`
/// threads (0: all hardware threads; bounded as Options::threads).
Bounds finiteBounds(const double* xyz, std::size_t count, int threads = 1);

} // namespace fd3

#endif
