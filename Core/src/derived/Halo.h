// The halo of a piece of a distributed point set (see Halo.cxx), gathered from the tetrahedra and
// hull faces of any mesh: an output Triangulation or a live IncrementalDelaunay.
#ifndef fd3_Halo_h
#define fd3_Halo_h

#include "fd3/Distributed.h"

#include <cmath>

namespace fd3
{

class HaloBuilder
{
public:
  /// With `heaviest`, the largest weight of any point of any piece, the tetrahedra are weighted
  /// (see Halo.cxx): weights, points and boxes then share one frame.
  explicit HaloBuilder(const std::vector<Bounds>& boxes, double heaviest = -HUGE_VAL);
  /// A finite tetrahedron: its points, their ids and, in a weighted mesh, their weights.
  void tetrahedron(
    const double* const p[4], const std::uint32_t ids[4], const double* weights = nullptr);
  /// A hull face, with a point on its inner side.
  void hullFace(const double* const p[3], const double* inner, const std::uint32_t ids[3]);
  /// For each box, the sorted ids of what meets it.
  std::vector<std::vector<std::uint32_t>> take();

private:
  const std::vector<Bounds>& boxes_;
  const double heaviest_;
  std::vector<std::vector<std::uint32_t>> halo_;
};

} // namespace fd3

#endif
