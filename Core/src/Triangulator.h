// Bowyer-Watson insertion as in the paper "Fast Delaunay triangulation in three dimensions":
//   insert(p) = locate (grid + onion search for a start, a walk to a tetrahedron in conflict)
//             -> digCavity (the core, grown through adjacency with exact insphere)
//             -> correctCavity (visibility and volume threshold: the core made star-shaped)
//             -> fillCavity (new tetrahedra linked through the boundary's edges, no search).
// Each step lives in the source file named after it.
#ifndef fd3_Triangulator_h
#define fd3_Triangulator_h

#include "BackgroundGrid.h"
#include "Cavity.h"
#include "Geometry.h"
#include "Predicates.h"
#include "TetMesh.h"
#include "fd3/Delaunay.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fd3
{

/// One vertex of the kernel, by insertion rank: its normalized coordinates, a live tetrahedron
/// incident to it, and its local number while a cavity is filled (kNoLocal otherwise). 32 bytes on
/// a 32-byte boundary: the coordinates that an insphere test loads bring the rest into cache, which
/// the fill that follows needs (fill phase 4% faster on 400k uniform points than with separate
/// arrays).
struct alignas(32) Vertex
{
  static constexpr std::uint16_t kNoLocal = 0xFFFF;
  Vertex() {} // uninitialized: the kernel writes millions of them right after allocating them
  double xyz[3];
  TetId tet;
  std::uint16_t localNumber;
};
static_assert(sizeof(Vertex) == 32, "a vertex fills half a cache line");

class Triangulator
{
public:
  /// `vertices` holds the normalized points by insertion rank (vertex id), all distinct, within
  /// `box`, and one more entry that stands for kInfinite in local numbering.
  Triangulator(std::vector<Vertex> vertices, const Box& box, const Options& options, Statistics& stats);

  /// Builds the first tetrahedron from vertices 0..3, which must be affinely independent.
  void start();

  /// Reserves the mesh for all `count` vertices, from the tetrahedra per vertex so far. Called once
  /// a BRIO round or two are in: they are random samples of the whole set, so the ratio is close to
  /// the final one (it grows slowly on surface samples, hence the margin).
  void reserveForAll(std::size_t count);

  /// Inserts vertex v; every vertex below v must have been handled before. Returns false when v
  /// is within the tolerance of an inserted vertex (vertexWithinTolerance()) and was left out.
  bool insert(VertId v);
  VertId vertexWithinTolerance() const { return nearVertex_; }

  const Predicates& predicates() const { return predicates_; }
  TetMesh& mesh() { return mesh_; }

  /// Frees the points, the grid and the scratch: only the mesh is left for the output.
  void releaseWorkspace();

  /// Exhaustive check of the invariants listed in TetMesh.h, of the vertices' records and, unless a volume
  /// threshold was used, of the local Delaunay property. Returns an empty string when all hold,
  /// else one line per violation (the first few of each kind).
  std::string checkMesh() const;

private:
  const double* point(VertId v) const { return vertices_[v].xyz; }
  std::size_t vertexCount() const { return vertices_.size() - 1; }
  /// The local-number entry of u, kInfinite's being the last.
  std::uint16_t& localNumber(VertId u)
  {
    return vertices_[u == kInfinite ? vertices_.size() - 1 : u].localNumber;
  }

  // Locate.cxx
  TetId startTet(VertId v) const;
  TetId walk(TetId from, VertId v);
  TetId locate(VertId v);
  // DigCavity.cxx
  int inSphereSoS(const VertId tet[4], VertId e)
  {
    const double* p[4] = {point(tet[0]), point(tet[1]), point(tet[2]), point(tet[3])};
    return predicates_.inSphereSoS(p, tet, point(e), e);
  }
  bool isBeyondHullFace(TetId ghost, VertId v);
  bool inConflict(TetId t, VertId v);
  VertId vertexWithin(double distance2, VertId v) const;
  void undoCavity();
  void digCavity(TetId base, VertId v);
  // CorrectCavity.cxx
  void correctCavity(VertId v);
  bool holdsPoint(TetId t, VertId v);
  double newTetShape(const BoundaryFacet& facet, VertId v);
  void giveBack(TetId t);
  void collectBoundary();
  bool dropOrphanGhosts(VertId v);
  bool keepEnclosedVertex(VertId v);
  // FillCavity.cxx
  void fillCavity(VertId v);
  bool linkByEdgeTable();
  void linkAroundEdge(std::size_t created, int face);

  std::uint32_t nextRandom();

  std::vector<Vertex> vertices_;
  Options options_;
  Statistics& stats_;
  Predicates predicates_;
  TetMesh mesh_;
  BackgroundGrid grid_;
  Cavity cavity_;
  VertId lastInserted_ = 0;
  VertId nearVertex_ = kNoVertex;
  std::uint64_t rng_;
  std::vector<std::uint32_t> vertexStamp_; // only with a volume threshold
  std::uint32_t stamp_ = 0;
};

} // namespace fd3

#endif
