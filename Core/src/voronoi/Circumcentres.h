// The Voronoi vertices: the tetrahedra's circumcentres (weighted: orthocentres), and the output's
// numbering of those in the box (Circumcentres.cxx; step 2 of VoronoiCells.cxx).
#ifndef fd3_voronoi_Circumcentres_h
#define fd3_voronoi_Circumcentres_h

#include "fd3/Voronoi.h"
#include "system/Threads.h"
#include "voronoi/Stars.h"

#include <cstddef>

namespace fd3::voronoi
{

using Doubles = VoronoiCells::Doubles;

/// Each tetrahedron's circumcentre, from its vertices in their order (in double-double where it
/// is flat), and whether it lies in the closed box. With `weights` (by point, as xyz), each
/// one's orthocentre, the power diagram's vertex.
void circumcentres(ThreadTeam& team, const double* xyz, const double* weights,
  const IdArray& tetrahedra, const Bounds& box, Doubles& centres, Flags& inBox);

/// The output point of each centre in the box, numbered in the tetrahedra's order: the centres
/// of each group, the ones its cell owns, follow each other, cell after cell. One entry more
/// than the tetrahedra: the count of centres before each one, and in all.
IdArray numberCentres(ThreadTeam& team, const Flags& inBox);

/// The centres in the box of the first `tets` tetrahedra (the cells' groups) into the output's
/// points.
void copyCentres(ThreadTeam& team, std::size_t tets, const Flags& inBox, const IdArray& pointOf,
  const Doubles& centres, VoronoiCells& cells);

} // namespace fd3::voronoi

#endif
