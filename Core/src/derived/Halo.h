// The halo of a piece of a distributed point set (see Halo.cxx), gathered from the tetrahedra and
// hull faces of any mesh: an output Triangulation or a live IncrementalDelaunay.
#ifndef fd3_Halo_h
#define fd3_Halo_h

#include "fd3/Distributed.h"

namespace fd3
{

class HaloBuilder
{
public:
  explicit HaloBuilder(const std::vector<Bounds>& boxes);
  /// A finite tetrahedron: its points and their ids.
  void tetrahedron(const double* const p[4], const std::uint32_t ids[4]);
  /// A hull face, with a point on its inner side.
  void hullFace(const double* const p[3], const double* inner, const std::uint32_t ids[3]);
  /// For each box, the sorted ids of what meets it.
  std::vector<std::vector<std::uint32_t>> take();

private:
  const std::vector<Bounds>& boxes_;
  std::vector<std::vector<std::uint32_t>> halo_;
};

} // namespace fd3

#endif
