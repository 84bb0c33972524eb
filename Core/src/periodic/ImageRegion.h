// A region of the covering's images (PeriodicDelaunay.h): where the certificate failed, the
// images that the covering must hold for a sphere there to be proven empty. A box; a ball in it
// about a failed sphere, where every axis is periodic; and for a hull face the face's outer side.
// The box alone about a wide sphere would take in far more images where points crowd its sides (a
// slab's surfaces across a vacuum, planes across a gap).
#ifndef fd3_ImageRegion_h
#define fd3_ImageRegion_h

#include "fd3/Bounds.h"

#include <algorithm>
#include <cmath>

namespace fd3
{

/// The points in `box`; where radius >= 0, within `radius` of `centre` too; and on the side of
/// the plane through `onPlane` that `normal` points to (a unit vector, or 0 for no plane).
struct ImageRegion
{
  Bounds box;
  double centre[3] = {0, 0, 0};
  double radius = -1;
  double onPlane[3] = {0, 0, 0};
  double normal[3] = {0, 0, 0};

  /// The region moved by `by` (each axis's shift times its period).
  ImageRegion moved(const double by[3]) const
  {
    ImageRegion out = *this;
    for (int k = 0; k < 3; ++k)
    {
      out.box.lo[k] += by[k];
      out.box.hi[k] += by[k];
      out.centre[k] += by[k];
      out.onPlane[k] += by[k];
    }
    return out;
  }

  /// The region grown by `by` all round: its box, its ball and its side.
  ImageRegion grown(double by) const
  {
    ImageRegion out = *this;
    for (int k = 0; k < 3; ++k)
    {
      out.box.lo[k] -= by;
      out.box.hi[k] += by;
      out.onPlane[k] -= by * normal[k];
    }
    if (radius >= 0)
      out.radius += by;
    return out;
  }

  /// Whether p lies in the ball and on the plane's side, as floats evaluate it (the box is the
  /// caller's: PeriodicDelaunay tests it in whole periods).
  bool ballAndSideHold(const double p[3]) const
  {
    double distance = 0, height = 0;
    for (int k = 0; k < 3; ++k)
    {
      distance += (p[k] - centre[k]) * (p[k] - centre[k]);
      height += normal[k] * (p[k] - onPlane[k]);
    }
    return height >= 0 && (radius < 0 || distance <= radius * radius);
  }

  /// Whether it has a plane.
  bool sided() const { return normal[0] != 0 || normal[1] != 0 || normal[2] != 0; }

  /// Whether a sphere lies in a region with no plane: `sphere` bounds it and `r` about `c` holds
  /// it. It must stay clear of the ball's side by more than the roundings of ballAndSideHold(),
  /// made in other units (`most`: the largest magnitude of a coordinate).
  bool holds(const Bounds& sphere, const double c[3], double r, double most) const
  {
    double apart = 0; // the centres' squared distance
    bool within = true;
    for (int k = 0; k < 3; ++k)
    {
      within = within && sphere.lo[k] >= box.lo[k] && sphere.hi[k] <= box.hi[k];
      apart += (c[k] - centre[k]) * (c[k] - centre[k]);
    }
    const double slack = 1e-12 * (most + r + std::max(radius, 0.0));
    return within && (radius < 0 || std::sqrt(apart) + r + slack <= radius);
  }

  enum class Overlap
  {
    None, ///< no point within `within` lies in the region
    Some, ///< some may
    All   ///< every one does
  };
  /// How the points within `within` (a box) lie in the region, from its corners.
  Overlap overlap(const Bounds& within) const
  {
    bool all = true, none = false;
    double nearest = 0, farthest = 0; // squared distances of the box from the centre
    double lowest = 0, highest = 0;   // heights of its corners over the plane
    for (int k = 0; k < 3; ++k)
    {
      all = all && within.lo[k] >= box.lo[k] && within.hi[k] <= box.hi[k];
      none = none || within.hi[k] < box.lo[k] || within.lo[k] > box.hi[k];
      const double below = centre[k] - within.hi[k], above = within.lo[k] - centre[k];
      const double gap = std::max({below, above, 0.0});
      const double reach = std::max(std::fabs(below), std::fabs(above));
      nearest += gap * gap;
      farthest += reach * reach;
      const double low = normal[k] > 0 ? within.lo[k] : within.hi[k];
      const double high = normal[k] > 0 ? within.hi[k] : within.lo[k];
      lowest += normal[k] * (low - onPlane[k]);
      highest += normal[k] * (high - onPlane[k]);
    }
    const double r2 = radius * radius;
    if (none || highest < 0 || (radius >= 0 && nearest > r2))
      return Overlap::None;
    return all && lowest >= 0 && (radius < 0 || farthest <= r2) ? Overlap::All : Overlap::Some;
  }
};

} // namespace fd3

#endif
