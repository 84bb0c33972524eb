// The Delaunay tessellation field estimate (Density.cxx) of tetrahedra on corners of their own,
// for a periodic piece, whose tetrahedra are on the images of its covering.
#ifndef fd3_Density_h
#define fd3_Density_h

#include "fd3/Delaunay.h"

#include <cstdint>
#include <vector>

namespace fd3
{

/// densities() of `count` points from tetrahedra `tets` on corners at `corners` (3 each), each
/// corner c counted at the point source[c], or at none where that is `count` or more; a point's
/// mass goes to representative[i], none where that is `count` or more (its density is then NaN).
std::vector<double> densitiesOfCorners(std::size_t count, const IdArray& tets,
  const double* corners, const std::uint32_t* source, const std::uint32_t* representative);

} // namespace fd3

#endif
