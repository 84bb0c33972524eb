// One generator's Voronoi cell from its star (CellBuilder.cxx; step 4 of VoronoiCells.cxx).
#ifndef fd3_voronoi_CellBuilder_h
#define fd3_voronoi_CellBuilder_h

#include "fd3/Voronoi.h"
#include "voronoi/BoxClip.h"
#include "voronoi/Stars.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace fd3::voronoi
{

/// Marks a cell's own vertex (a crossing of the box) in a stretch's output, before the join
/// numbers it.
constexpr std::uint32_t kOwnVertex = 0x80000000u;

/// The clipped cells of one stretch of generators, with vertex ids that are tetrahedra (their
/// circumcentres) or kOwnVertex + the index of one of the cell's crossings of the box.
struct Stretch
{
  std::vector<std::uint32_t> cells;      ///< index of each cell among all
  std::vector<std::uint32_t> faceCounts; ///< per cell
  std::vector<std::uint32_t> crossings;  ///< per cell
  std::vector<std::uint32_t> faceSizes;  ///< per face
  std::vector<std::uint32_t> vertices;
  std::vector<std::uint32_t> pointCounts; ///< per cell: its distinct vertices, in `points`
  std::vector<std::uint32_t> points;      ///< as `vertices` names them
  std::vector<std::uint32_t> neighbors;   ///< per face
  std::vector<double> crossingPoints;
  std::vector<double> volumes, areas;
};

/// What every cell is built from, shared by the threads (read only while cells are built).
struct CellSources
{
  const double* xyz;      ///< the points, along the curve
  const IdArray& inputId; ///< of each point but the far ones
  const Stars& stars;
  const Bounds& box;
  bool polyhedra; ///< VoronoiOptions::polyhedra
  /// Per tetrahedron: its centre, while the clipped cells are built; then null, and the centres
  /// in the box are read from `points` through `pointOf`.
  const double* centres = nullptr;
  const std::uint32_t* pointOf = nullptr; ///< per tetrahedron whose centre is an output point
  const double* points = nullptr;
};

/// Builds one generator's cell after another (one builder per thread).
class CellBuilder
{
public:
  /// A builder for cells of a mesh of `vertices` vertices.
  CellBuilder(const CellSources& sources, std::size_t vertices);

  /// The faces of p's cell before any clipping, as ring steps: the ring of its star's tetrahedra
  /// about each edge (p, q), turning counter-clockwise about p -> q, so that the face is
  /// counter-clockwise seen from outside. The link vertices q are numbered as the star meets them;
  /// the star's order is the points' alone (Stars), and so are these numbers, the order of the
  /// faces (by them) and where each ring starts (at the last of the star's tetrahedra in it).
  void trace(std::uint32_t p);

  /// A cell inside the box, written where `at` says: its faces are the rings as they are, each
  /// traced straight into the output (the volume's and area's sums beside the ring's steps, which
  /// wait on each other); its points, each once, are its star's tetrahedra's centres.
  template <bool Polyhedra>
  void emitWhole(
    std::uint32_t p, std::size_t cell, std::size_t face, std::size_t vertex, VoronoiCells& out);

  /// A cell that leaves the box, clipped by its six planes, into `out`.
  void emitClipped(std::uint32_t p, std::uint32_t cell, Stretch& out);

private:
  /// A tetrahedron's step in the ring about (p, q), kept under the key of (q, the link vertex of
  /// the face it enters by): `next` is the key of the step after it, `star` the tetrahedron's
  /// index in the star, `cell` the cell that wrote it.
  struct RingStep
  {
    std::uint64_t next;
    std::uint32_t star, cell;
  };

  /// A face's neighbour as the output names it: the input id of a point, or a box wall.
  std::uint32_t inputId(std::uint32_t neighbor) const
  {
    return neighbor < in_.inputId.size() ? in_.inputId[neighbor] : neighbor;
  }
  static int localIndex(const std::uint32_t* vertices, std::uint32_t v)
  {
    return (vertices[1] == v) + 2 * (vertices[2] == v) + 3 * (vertices[3] == v);
  }
  const double* centre(std::uint32_t t) const
  {
    return in_.centres ? in_.centres + 3 * std::size_t(t)
                       : in_.points + 3 * std::size_t(in_.pointOf[t]);
  }

  /// The star's tetrahedra into star_, their link vertices numbered by linkIndex(v), and each
  /// one's steps in the rings about its three link vertices, through step(key).
  template <typename LinkIndex, typename Step>
  void addStar(std::uint32_t p, LinkIndex linkIndex, Step step);
  /// v's index in link_, which it joins if new (without a branch: new or not is a coin toss).
  std::uint32_t denseLinkIndex(std::uint32_t v);
  std::uint32_t largeLinkIndex(std::uint32_t v);
  const RingStep& stepAt(std::uint64_t key) const;
  /// The rings, into loops_ / faceStart_: face q's is the ring about link_[q].
  void traceRings();
  void makePolyhedron();

  /// Links of up to this many vertices are numbered in linkOf_ and have their ring steps in a
  /// square table.
  static constexpr std::size_t kDenseLinks = 256;
  /// How far ahead in a star's list its tetrahedra are fetched.
  static constexpr std::size_t kAhead = 8;
  static constexpr std::uint16_t kNoLink = 0xFFFF;

  const CellSources& in_;
  // One cell's scratch, kept between cells for its memory.
  std::vector<std::uint32_t> star_; ///< the tetrahedra around the generator
  std::vector<std::uint32_t> link_; ///< the vertices joined to the generator, as met
  /// Each vertex's index in link_ while a cell is traced (kNoLink otherwise): two bytes a vertex
  /// per thread, against a hash map's several lookups.
  std::vector<std::uint16_t> linkOf_;
  std::unordered_map<std::uint32_t, std::uint32_t> linkOfLarge_;
  std::vector<RingStep> steps_; ///< links x links, by (q, from)
  std::unordered_map<std::uint64_t, RingStep> stepsLarge_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> firstFrom_; ///< per link vertex: where its ring starts
  std::size_t links_ = 0; ///< the link's vertices: 2 + n/2 for a star of n tetrahedra
  std::size_t met_ = 0;   ///< the link's vertices met so far
  /// A clipped cell's local vertex of each star tetrahedron, and its crossing of each local
  /// vertex (kNone where it has none yet).
  std::vector<std::uint32_t> localOf_, crossingOf_;
  std::vector<bool> listed_; ///< per local vertex of a clipped cell: among its points yet
  std::vector<std::uint32_t> loops_, faceStart_;
  std::vector<std::array<double, 3>> fromGenerator_; ///< per star tetrahedron: its centre - p
  std::vector<std::uint32_t> pointOf_;               ///< per star tetrahedron: its centre's point
  Polyhedron cell_;
  BoxClipper clipper_;
};

} // namespace fd3::voronoi

#endif
