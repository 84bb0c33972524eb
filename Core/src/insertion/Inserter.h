// Bowyer-Watson insertion as in the paper "Fast Delaunay triangulation in three dimensions", by
// one thread:
//   insert(p) = locate (grid + onion search for a start, a walk to a tetrahedron in conflict)
//             -> digCavity (the core, grown through adjacency with exact insphere)
//             -> correctCavity (visibility and volume threshold: the core made star-shaped)
//             -> fillCavity (new tetrahedra linked through the boundary's edges, no search).
// Each step lives in the source file named after it. Several inserters may work on one mesh at
// once (ParallelInsertion.cxx): each in a region of its own (Region), or each holding the
// tetrahedra it touches in an owner table (a locking pass).
#ifndef fd3_Inserter_h
#define fd3_Inserter_h

#include "TetMesh.h"
#include "exact/Predicates.h"
#include "fd3/Delaunay.h"
#include "insertion/BackgroundGrid.h"
#include "insertion/Cavity.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace fd3
{

/// One vertex of the kernel, by insertion rank: its normalized coordinates, a live tetrahedron
/// incident to it, and the id of the input point it is. 32 bytes on a 32-byte boundary: the
/// coordinates that an insphere test loads bring the rest into cache, which the fill that follows
/// needs (faster than separate arrays). While a cavity is
/// filled, `tet` of each of its boundary's vertices holds the vertex's local number instead,
/// tagged (FillCavity.cxx): a mark per vertex that needs no room of its own.
struct alignas(32) Vertex
{
  Vertex() {} // uninitialized: the kernel writes millions of them right after allocating them
  double xyz[3];
  TetId tet;
  std::uint32_t point;
};
static_assert(sizeof(Vertex) == 32, "a vertex fills half a cache line");

using VertexArray = std::vector<Vertex, BulkAllocator<Vertex>>;

/// The triangulation under construction, shared by every inserter.
struct Mesh
{
  VertexArray vertices; ///< by insertion rank
  /// The vertices' weights, by insertion rank, in the frame's units (squared lengths); empty for
  /// a Delaunay (unweighted) mesh. A weighted mesh is the regular tetrahedralization, whose
  /// hidden points are not vertices: their Vertex::tet is kNoTet.
  std::vector<double> weights;
  TetMesh tets;
  BackgroundGrid grid;
  Options options; ///< in normalized units

  const double* point(VertId v) const { return vertices[v].xyz; }
  bool weighted() const { return !weights.empty(); }
};

/// Which thread holds each tetrahedron during a locking pass: 0 for none, else the holder's
/// number (an inserter's, from 1). One byte per slot, made for the pass.
using OwnerTable = std::atomic<std::uint8_t>;

/// The part of space where one inserter may change the mesh during a parallel pass: a half-open
/// box. A tetrahedron is the inserter's when its four vertices are in it (the ghost vertex is in
/// every region). An inserter reads only tetrahedra with three vertices or more in its region, and
/// writes only those: no tetrahedron has three vertices in each of two regions, so no two
/// inserters ever touch the same one.
struct Region
{
  double lo[3] = {-INFINITY, -INFINITY, -INFINITY};
  double hi[3] = {INFINITY, INFINITY, INFINITY};

  bool contains(const double* p) const
  {
    return lo[0] <= p[0] && p[0] < hi[0] && lo[1] <= p[1] && p[1] < hi[1] && lo[2] <= p[2] &&
      p[2] < hi[2];
  }
};

class Inserter
{
public:
  /// `predicates` are adapted to the mesh's points (each inserter has a copy: they count).
  Inserter(Mesh& mesh, SlotPool& pool, const Predicates& predicates, std::uint64_t seed);

  /// Builds the first tetrahedron from vertices 0..3, which must be affinely independent.
  void start();

  /// Restricts this inserter to `region` for a parallel pass, starting from tetrahedron `start`,
  /// which must be the region's; unrestricted() lifts it.
  void restrictTo(const Region& region, TetId start);
  void unrestricted();
  /// For a locking pass: from now on, this inserter reads and writes a tetrahedron only once it
  /// holds it in `owners` (`slots` of them) as number `me`; an insertion that meets one another
  /// inserter holds is put off. Its pool's free slots are its own already (the pass marks them).
  /// unlocked() ends it.
  void lockIn(OwnerTable* owners, std::size_t slots, std::uint8_t me);
  void unlocked();

  /// How an inserter may touch the mesh: alone (Free), in its region (Region), or holding what it
  /// touches in an owner table (Locking). The steps of an insertion are compiled once for each,
  /// so that one that works alone makes none of the others' checks.
  enum class Access
  {
    Free,
    Region,
    Locking
  };

  enum class Outcome
  {
    Inserted,
    Deferred,  ///< it would change the mesh outside the region, or the region is full: nothing done
    Duplicate, ///< v repeats a vertex of the mesh (only looked for after lookForDuplicates())
    Hidden     ///< weighted: v conflicts with no tetrahedron, so it is no vertex (hidden())
  };
  /// Inserts vertex v, a point of the region.
  Outcome insert(VertId v)
  {
    if (owners_)
      return insertAs<Access::Locking>(v);
    if (restricted_)
      return insertAs<Access::Region>(v);
    return insertAs<Access::Free>(v);
  }

  /// From now on, every point is first located in the tetrahedron that contains it (not only one
  /// in conflict), which has as vertex any vertex that the point repeats: that one is then
  /// recorded in duplicates() and the point left out. For points added to a finished mesh, which
  /// the initial sort did not merge.
  void lookForDuplicates() { lookForDuplicates_ = true; }
  /// (repeating vertex, vertex it repeats), in the order met.
  const std::vector<std::pair<VertId, VertId>>& duplicates() const { return duplicates_; }
  /// Weighted: the vertices this inserter found hidden, new points and vertices that a heavier
  /// point's insertion took out of the mesh, in the order found.
  const std::vector<VertId>& hidden() const { return hidden_; }

  /// A tetrahedron in conflict with vertex v, reading only (for the start of a parallel pass).
  TetId locateForStart(VertId v) { return locate(v, gridCell(v)); }
  bool isOwned(TetId t) const
  {
    return owners_ ? owners_[t].load(std::memory_order_relaxed) == me_
                   : !restricted_ || allVerticesInRegion(t);
  }
  /// Whether the threading contract (TetMesh.h) lets this inserter read and write t now: always
  /// when unrestricted, else when three of t's vertices or more are in its region.
  bool mayTouch(TetId t) const;

  const Statistics& stats() const { return stats_; }
  /// The last insertion's cavity: the tetrahedra it deleted (freed slots now) and made.
  const Cavity& lastCavity() const { return cavity_; }
  const Predicates& predicates() const { return predicates_; }
  /// Takes the tuning of `tuned`, after points were added to the mesh.
  void retune(const Predicates& tuned) { predicates_.tuneLike(tuned); }

private:
  const double* point(VertId v) const { return mesh_.point(v); }
  bool allVerticesInRegion(TetId t) const;
  bool inRegion(VertId u) const
  {
    return !restricted_ || u == kInfinite || region_.contains(point(u));
  }
  /// The field of u that holds its local number during a fill (its tet); kInfinite's, which only
  /// a ghost's facet holds (MayBeGhost), is this inserter's own. In a locking pass, an entry of the
  /// cavity's own table.
  template <Access A, bool MayBeGhost>
  TetId& localNumberSlot(Vertex* vertices, VertId u)
  {
    if constexpr (A == Access::Locking)
      return cavity_.localNumbers.slot(u);
    if constexpr (MayBeGhost)
      if (u == kInfinite)
        return ghostTet_;
    return vertices[u].tet;
  }
  /// Sets the tetrahedron of u (in a locking pass, other inserters may read it at the same time).
  template <Access A = Access::Locking>
  void setVertexTet(VertId u, TetId t)
  {
    if (u == kInfinite)
      return;
    if constexpr (A == Access::Locking)
      relaxedStore(mesh_.vertices[u].tet, t);
    else
      mesh_.vertices[u].tet = t;
  }
  /// Starts loading t's record and, in a locking pass, its owner, which acquire() reads first.
  void prefetchTet(TetId t) const
  {
    tets_.prefetch(t);
    if (owners_)
      prefetch(owners_ + t);
  }
  /// In a locking pass: whether this inserter holds t now, taking it if no one does.
  bool acquire(TetId t);
  /// Whether the walk may go on into t, entered through its face `entryFace` (-1 for the start):
  /// in a region, when t is the inserter's; in a locking pass, when it could take t and t is live;
  /// the walk then lets go of the one it leaves. Alone, always: inline, without a call per step.
  bool mayEnter(TetId t, int entryFace)
  {
    return (!restricted_ && !owners_) || mayEnterShared(t, entryFace);
  }
  bool mayEnterShared(TetId t, int entryFace);
  /// Counts a put-off insertion, after whatever it did was undone.
  Outcome deferred();
  /// Lets go of the tetrahedra taken for the insertion that ended, except the slots it freed,
  /// which its pool keeps.
  void releaseHeld();

  // Locate.cxx
  /// v's cell of the background grid, where there is one.
  BackgroundGrid::Cell gridCell(VertId v) const
  {
    return mesh_.grid.enabled() ? mesh_.grid.cellOf(point(v)) : BackgroundGrid::Cell{};
  }
  TetId startTet(VertId v, const BackgroundGrid::Cell& cell);
  TetId liveStart();
  TetId regionStart(VertId v, const BackgroundGrid::Cell& cell) const;
  template <bool Weighted>
  TetId walk(TetId from, VertId v);
  /// A walk's way over the hull, from ghost to ghost.
  struct HullWalk
  {
    int steps = 0;
    FaceCode entry = 0; ///< the way inside from the ghost where the walk came onto the hull
  };
  enum class AtGhost
  {
    Ends,  ///< the walk ends at the ghost
    Lost,  ///< the walk ends without a tetrahedron (lockLost_)
    Steps, ///< the walk goes on
  };
  AtGhost walkAtGhost(
    TetId ghost, VertId v, bool toFirstConflict, int entryFace, HullWalk& hull, FaceCode& next);
  /// Whether the probe's first filter proves v in conflict with the finite tetrahedron tv (of
  /// points q).
  bool provenInConflict(const InSphereProbe& probe, const double* const q[4], const VertId*)
  {
    return probe.provenInside(q[0], q[1], q[2], q[3]);
  }
  bool provenInConflict(const PowerProbe& probe, const double* const q[4], const VertId tv[4])
  {
    double weights[4];
    weightsOf(tv, weights);
    return probe.provenInside(q, weights);
  }
  TetId scanForBase(VertId v, bool toFirstConflict);
  TetId locate(VertId v, const BackgroundGrid::Cell& cell);
  /// The vertex of base (which contains v's point) that v repeats, or kNoVertex.
  VertId repeatedVertex(TetId base, VertId v) const;
  template <Access A>
  Outcome insertAs(VertId v);

  /// The weights of the finite tetrahedron tv's vertices (weighted meshes only).
  void weightsOf(const VertId tv[4], double out[4]) const
  {
    for (int k = 0; k < 4; ++k)
      out[k] = mesh_.weights[tv[k]];
  }
  // DigCavity.cxx
  /// Whether e conflicts with the finite tetrahedron `tet`, ties broken symbolically: e in its
  /// circumsphere or, weighted, of negative power distance to its orthogonal sphere.
  int conflictSoS(const VertId tet[4], VertId e)
  {
    const Vertex* v = mesh_.vertices.data();
    const double* p[4] = {v[tet[0]].xyz, v[tet[1]].xyz, v[tet[2]].xyz, v[tet[3]].xyz};
    if (!mesh_.weighted())
      return predicates_.inSphereSoS(p, v[e].xyz);
    double weights[4];
    weightsOf(tet, weights);
    return predicates_.powerTestSoS(p, v[e].xyz, weights, mesh_.weights[e]);
  }
  /// The cavity search's conflict tests for v: InSphereProbe, or weighted, PowerProbe.
  template <bool Weighted>
  auto conflictProbe(VertId v)
  {
    if constexpr (Weighted)
      return PowerProbe(predicates_, point(v), mesh_.weights[v]);
    else
      return InSphereProbe(predicates_, point(v));
  }
  bool isBeyondHullFace(TetId ghost, VertId v);
  /// Whether v lies in t's circumsphere. Inline: it runs tens of times per insertion, and a call
  /// costs a few percent of the run.
  bool inConflict(TetId t, VertId v)
  {
    VertId tv[4];
    tets_.vertices(t, tv);
    if (tv[3] == kInfinite)
      return ghostInConflict(t, v);
    if (mesh_.weighted())
      return conflictSoS(tv, v) > 0;
    const Vertex* p = mesh_.vertices.data();
    const double* q[4] = {p[tv[0]].xyz, p[tv[1]].xyz, p[tv[2]].xyz, p[tv[3]].xyz};
    return predicates_.insideSoS(q, p[v].xyz);
  }
  bool ghostInConflict(TetId ghost, VertId v);
  bool openConflict(TetId t, VertId v);
  bool onHullPlaneInConflict(TetId ghost, VertId v);
  void undoCavity();
  /// Room for `count` entries or more in the cavity search's lists (deleted, boundary); returns
  /// the room.
  std::size_t makeRoomInCavityLists(std::size_t count);
  /// The cavity search's conflict test: the insphere test, its static filter or its lifts' filter
  /// first (Predicates::prefersLiftsFilter()), or the power test. A template parameter, so that
  /// the search does not ask which on every test.
  enum class ConflictTest
  {
    InSphereStatic,
    InSphereLifts,
    Power
  };
  template <Access A, ConflictTest Test>
  bool digCavity(TetId base, VertId v);
  template <Access A>
  bool digCavity(TetId base, VertId v)
  {
    if (mesh_.weighted())
      return digCavity<A, ConflictTest::Power>(base, v);
    return predicates_.prefersLiftsFilter() ? digCavity<A, ConflictTest::InSphereLifts>(base, v)
                                            : digCavity<A, ConflictTest::InSphereStatic>(base, v);
  }
  // Weighted (HiddenPoints.cxx)
  /// Whether the base that the walk found for v, which contains v's point or is a ghost whose
  /// hull face v lies beyond, conflicts with v: if not, v is hidden, since every tetrahedron in
  /// conflict with a point is connected to the one that contains it.
  bool baseInConflict(TetId base, VertId v);
  /// The vertices of the cavity's tetrahedra that might lose all of theirs, before the fill:
  /// those the fill leaves on no tetrahedron are hidden by v (hideEnclosedVertices()).
  void collectCavityVertices();
  void hideEnclosedVertices();
  void hide(VertId u);
  // CorrectCavity.cxx
  void correctCavity(VertId v);
  bool holdsPoint(TetId t, VertId v);
  double newTetShape(FaceCode facet, VertId v);
  void giveBack(TetId t);
  void collectBoundary();
  bool dropOrphanGhosts(VertId v);
  bool keepEnclosedVertex(VertId v);
  // FillCavity.cxx
  template <Access A>
  bool fillCavity(VertId v);
  template <Access A>
  bool createAndLink(VertId v);
  void linkByRotation();
  void linkAroundEdge(std::size_t created, int face);

  std::uint32_t nextRandom();

  Mesh& mesh_;
  TetMesh& tets_; // mesh_.tets
  SlotPool& pool_;
  Statistics stats_;
  Predicates predicates_;
  Cavity cavity_;
  Region region_;
  bool restricted_ = false;
  bool lookForDuplicates_ = false;
  std::vector<std::pair<VertId, VertId>> duplicates_;
  std::vector<VertId> hidden_;
  struct CavityVertex
  {
    VertId vertex;
    TetId tet; ///< its Vertex::tet, deleted by the cavity
  };
  std::vector<CavityVertex> cavityVertices_; // weighted only: room for every cavity vertex
  std::size_t cavityCandidates_ = 0;         // the first ones, collectCavityVertices()'s
  // The start of the next walk: the last inserted vertex (unrestricted), or, restricted, a
  // tetrahedron of the region near the last point: the last one created, or the base found for a
  // point that was put off (both the inserter's, unlike a vertex's tetrahedron).
  VertId lastInserted_ = 0;
  TetId regionStart_ = 0;
  TetId ghostTet_ = kUnnumbered; // the ghost vertex's stand-in for Vertex::tet, during fills only
  // How many steps the next walk may take over the hull (Locate.cxx): one more after each walk
  // that found its way there, half after each that ran out of them.
  int hullStepCap_ = 1;
  std::uint64_t rng_;
  std::vector<std::uint32_t> vertexStamp_; // only with a volume threshold
  std::uint32_t stamp_ = 0;
  // A locking pass's: the table, this inserter's number in it, and what it holds for the insertion
  // under way.
  OwnerTable* owners_ = nullptr;
  std::size_t ownerSlots_ = 0;
  std::uint8_t me_ = 0;
  std::vector<TetId> held_;
  // Set when a test needed a tetrahedron another inserter holds (a ghost's verdict on its plane
  // is the finite tetrahedron's behind it): the insertion under way is put off.
  bool lockLost_ = false;
};

} // namespace fd3

#endif
