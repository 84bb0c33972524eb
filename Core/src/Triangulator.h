// Bowyer-Watson insertion as in the paper "Fast Delaunay triangulation in three dimensions":
//   insert(p) = locate (grid + onion search, random walk to the base)
//             -> digCavity (the core, grown from the base through adjacency with insphere)
//             -> correctCavity (visibility and volume threshold: the core made star-shaped)
//             -> fillCavity (new tetrahedra linked by rotating about the core's boundary edges).
// Each step lives in the source file named after it.
#ifndef fd3_Triangulator_h
#define fd3_Triangulator_h

#include "BackgroundGrid.h"
#include "Predicates.h"
#include "TetMesh.h"
#include "fd3/Delaunay.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace fd3
{

/// A face of the cavity's boundary: face `face` of the deleted tetrahedron `inner`.
struct BoundaryFacet
{
  TetId inner;
  int face;
};

class Triangulator
{
public:
  /// `xyz` holds the normalized points by insertion rank (vertex id).
  Triangulator(std::vector<double> xyz, const Options& options, Statistics& stats);

  /// Builds the first tetrahedron from vertices 0..3, which must be affinely independent.
  void start();

  enum class Outcome
  {
    Inserted,
    Duplicate,  ///< an exact copy of an earlier vertex
    TooClose    ///< within the tolerance of an earlier vertex
  };
  /// Inserts vertex v; every vertex below v must have been handled before.
  Outcome insert(VertId v);

  /// The earlier vertex that made insert() return Duplicate or TooClose.
  VertId duplicateOf() const { return duplicateOf_; }

  const Predicates& predicates() const { return predicates_; }
  TetMesh& mesh() { return mesh_; }
  const TetMesh& mesh() const { return mesh_; }
  const std::vector<double>& points() const { return xyz_; }

  /// Frees the points, the grid and the scratch buffers: only the mesh is left for the output.
  void releaseWorkspace();

  /// Exhaustive structural and geometric check of the invariants listed in TetMesh.h and of the
  /// local Delaunay property (unless a volume threshold was used). Returns an empty string when valid.
  std::string checkMesh();

private:
  const double* point(VertId v) const { return xyz_.data() + 3 * std::size_t(v); }

  // Locate.cxx
  TetId startTet(VertId v);
  TetId walk(TetId from, VertId v);
  TetId locate(VertId v);
  // DigCavity.cxx
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
  bool releaseEnclosedVertex(VertId v);
  // FillCavity.cxx
  void fillCavity(VertId v);
  bool linkByEdgeTable();
  void linkAroundEdge(std::size_t created, int face);

  std::uint32_t nextRandom();

  std::vector<double> xyz_;
  Options options_;
  Statistics& stats_;
  Predicates predicates_;
  TetMesh mesh_;
  BackgroundGrid grid_;
  // A live tetrahedron incident to each inserted vertex; one more entry stands for kInfinite.
  std::vector<TetId> vertexTet_;
  TetId lastCreated_ = 0;
  VertId duplicateOf_ = 0;
  std::uint64_t rng_;

  // Per-insertion scratch, reused so that the steady state allocates nothing.
  std::vector<TetId> cavity_;
  std::vector<TetId> rejected_;
  std::vector<BoundaryFacet> boundary_;
  std::vector<TetId> created_;
  // linkByEdgeTable's: the boundary's vertices by local number, with a new tetrahedron on each
  // (while the table is built, vertexTet_ holds kLocalMark | local number for them), the face code
  // at each directed boundary edge, and each new interior face with the entry of its reversed edge.
  static constexpr std::uint32_t kMaxLocalVertices = 64;
  static constexpr TetId kLocalMark = 0x80000000u; // above any tetrahedron id (< 2^30)
  std::vector<VertId> localVertex_ = std::vector<VertId>(kMaxLocalVertices + 4);
  std::vector<TetId> localTet_ = std::vector<TetId>(kMaxLocalVertices + 4);
  std::vector<FaceCode> edgeFace_ = std::vector<FaceCode>(kMaxLocalVertices * kMaxLocalVertices);
  std::vector<std::pair<FaceCode, std::uint32_t>> interiorFaces_;
  std::vector<std::uint32_t> vertexStamp_; // only with a volume threshold
  std::uint32_t stamp_ = 0;
};

} // namespace fd3

#endif
