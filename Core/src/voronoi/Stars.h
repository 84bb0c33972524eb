// The stars of the vertices of a tetrahedralization, in an order that the points alone decide
// (Stars.cxx; steps 2 and 3 of VoronoiCells.cxx).
#ifndef fd3_voronoi_Stars_h
#define fd3_voronoi_Stars_h

#include "fd3/Voronoi.h"
#include "system/Threads.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fd3::voronoi
{

/// One byte per tetrahedron or vertex, written by the threads that own them (no zero fill first).
using Flags = std::vector<std::uint8_t, BulkAllocator<std::uint8_t>>;

/// Every vertex's star, from the tetrahedra grouped by their lowest vertex (the group's owner):
/// v's star is its own group and the tetrahedra of lower vertices' groups that hold it.
struct Stars
{
  /// 4 vertices each, in sortVertices' order; vertex v's group is [ownStart[v], ownStart[v + 1]),
  /// ordered by the tetrahedra's other three vertices, an order the points alone decide.
  IdArray tetrahedra;
  VoronoiCells::Offsets ownStart;
  /// The tetrahedra that hold v but not as their lowest vertex, in the groups' order:
  /// others[otherStart[v], otherStart[v + 1]).
  IdArray others;
  VoronoiCells::Offsets otherStart;
  /// Whether a tetrahedron of the vertex's star has its centre outside the box: its cell is
  /// clipped.
  Flags clipped;

  std::size_t sizeOf(std::uint32_t v) const
  {
    return ownStart[v + 1] - ownStart[v] + otherStart[v + 1] - otherStart[v];
  }
};

/// Each tetrahedron's vertices in ascending order, the last two exchanged where that order is an
/// odd permutation of the mesh's, so that it stays positively oriented. The mesh's rotation of
/// the vertices varies with the thread count; this order, the centres' rounding and everything
/// built from them depend on the points alone.
void sortVertices(ThreadTeam& team, Triangulation& mesh);

/// The mesh's tetrahedra whose lowest vertex is below `owners` grouped by that vertex into
/// stars.tetrahedra (the mesh's array goes to stars.others), and each vertex's other tetrahedra
/// counted. The others make no cell: a mesh's halo or periodic images bring many. Each thread
/// scans every tetrahedron for the vertices of its own range, so that no two threads write one
/// vertex's entries.
void groupByLowestVertex(
  ThreadTeam& team, Triangulation& mesh, std::size_t vertices, std::size_t owners, Stars& stars);

/// Each vertex's other tetrahedra (those of lower vertices' groups that hold it), and whether
/// its cell is clipped (a centre of its star is not inBox).
void listOthers(ThreadTeam& team, const Flags& inBox, Stars& stars);

} // namespace fd3::voronoi

#endif
