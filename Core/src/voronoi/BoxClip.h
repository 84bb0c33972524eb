// A cell cut by the walls of its box (BoxClip.cxx; step 5 of VoronoiCells.cxx).
#ifndef fd3_voronoi_BoxClip_h
#define fd3_voronoi_BoxClip_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fd3::voronoi
{

constexpr std::uint32_t kNone = 0xFFFFFFFFu;

/// A cell as a polyhedron of local vertices, while it is clipped.
struct Polyhedron
{
  std::vector<std::array<double, 3>> x;
  std::vector<std::uint32_t> tet;       ///< the tetrahedron of a circumcentre, kNone for a crossing
  std::vector<std::uint32_t> faceStart; ///< faces.size() + 1 entries
  std::vector<std::uint32_t> loops;
  std::vector<std::uint32_t> neighbors;
};

/// Clips polyhedra by the walls of a box, one wall at a time, its scratch kept between cells.
class BoxClipper
{
public:
  /// Keeps the part of `c` on the box's side of wall `wall` (0..5: xmin, xmax, ..., zmax), which
  /// lies at `bound` on its axis. The new face on the wall has the neighbour kBoxFace + wall.
  void clip(Polyhedron& c, int wall, double bound);

private:
  static void append(std::vector<std::uint32_t>& loops, std::size_t kept, std::uint32_t v);
  /// The point where edge (inside, outside) crosses the plane, the same for every cell around it.
  std::uint32_t crossing(
    Polyhedron& c, std::uint32_t inside, std::uint32_t outside, int axis, double bound);
  /// The new face on the plane: the cap edges chained into a loop. Where rounding cut a sliver of
  /// no width along an edge of the box, the edges make several loops: each becomes a face, and a
  /// loop of two edges (one there and back) none, so that every edge keeps its reverse.
  void closeCap(std::vector<std::uint32_t>& loops, std::vector<std::uint32_t>& faceStart,
    std::vector<std::uint32_t>& neighbors, std::uint32_t wall);

  /// The faces a clip keeps, swapped into the polyhedron.
  std::vector<std::uint32_t> keptLoops_, keptStarts_, keptNeighbors_;
  std::vector<std::array<std::uint32_t, 3>> crossings_;
  std::vector<std::pair<std::uint32_t, bool>> events_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> capEdges_;
  std::vector<bool> capUsed_;
};

} // namespace fd3::voronoi

#endif
