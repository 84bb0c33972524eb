// The triangulation's driver: the mesh that every inserter shares, one inserter and one slot pool
// per thread, and the order in which they insert the points: serially for the first BRIO rounds,
// then round by round in parallel (ParallelInsertion.cxx): in regions, one per thread, then in
// locking passes.
#ifndef fd3_Triangulator_h
#define fd3_Triangulator_h

#include "fd3/Bounds.h"
#include "fd3/Delaunay.h"
#include "insertion/Inserter.h"
#include "system/Threads.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fd3
{

class Partition; // ParallelInsertion.h, which builds on this file

class Triangulator
{
public:
  /// `vertices` holds the normalized points by insertion rank (vertex id), all distinct, within
  /// `box`, which the grid covers and which sets the predicates' static bounds until points
  /// beyond it are added. An inserter is made ready for each thread of `team`, which records
  /// every parallel pass.
  /// `anyMagnitude`: the points are not scaled into [-1, 1] (Predicates::allowAnyMagnitude()).
  /// `weights`, by vertex, in the frame's units, makes the mesh the regular tetrahedralization
  /// (Mesh::weights), inserted on one thread.
  Triangulator(VertexArray vertices, const Bounds& box, const Options& options, ThreadTeam& team,
    bool anyMagnitude, std::vector<double> weights = {});

  /// Inserts every vertex, the rounds of `roundStarts` (first vertex of each BRIO round) after the
  /// first tetrahedron, vertices 0..3. `progress` is called from this thread only; returns false
  /// when it asked to stop.
  bool insertAll(
    const std::vector<std::size_t>& roundStarts, const std::function<bool(double)>& progress);
  /// Appends `more` vertices (of `weights` on a weighted mesh, in the frame's units), distinct
  /// from each other and anywhere in the frame, and inserts them,
  /// in the rounds of `roundStarts` (indices into `more`). Those that repeat a vertex of the mesh
  /// are left out and listed in duplicates(). A periodic mesh takes their `images` too.
  bool insertMore(VertexArray more, std::vector<double> weights,
    const std::vector<std::size_t>& roundStarts, const std::function<bool(double)>& progress,
    const std::vector<ImageOf>& images = {});
  /// Makes the mesh periodic, before any insertion: its vertices are the periodic images of
  /// `images` (by vertex rank, in the frame's units), which the predicates then decide exactly.
  void useImages(std::vector<ImageOf> images);
  /// Appends `vertex` and inserts it on this thread, appending the finite tetrahedra the insertion
  /// deleted and made to `deleted` and `made`; false, with no change, when it repeats a vertex
  /// (listed in duplicates()).
  bool insertOne(const Vertex& vertex, std::vector<TetId>& deleted, std::vector<TetId>& made);

  /// The figures of every inserter, summed.
  Statistics statistics() const;
  /// (added vertex, vertex of the mesh it repeats) of every insertMore().
  std::vector<std::pair<VertId, VertId>> duplicates() const;
  /// Weighted: the vertices hidden, new points and vertices taken out, in no particular order.
  std::vector<VertId> hidden() const;
  /// Counters of every inserter's predicates, summed.
  void addPredicateCounts(Statistics& stats) const;

  /// Slots of the mesh, live or not: records() and releaseWorkspace() hold this many.
  std::size_t slots() const { return mesh_.tets.slots(); }
  /// The live mesh, to read.
  const TetMesh& tetrahedra() const { return mesh_.tets; }
  /// A copy of the mesh's records (TetMesh::copyRecords()).
  IdArray copyRecords() const { return mesh_.tets.copyRecords(); }
  /// The vertices, by insertion rank (each with its input point id).
  const VertexArray& vertices() const { return mesh_.vertices; }
  /// Weighted: the vertices' weights, by insertion rank, in the frame's units; else empty.
  const std::vector<double>& weights() const { return mesh_.weights; }
  /// Frees the grid and the inserters' scratch: only the mesh and its vertices are left for the
  /// output.
  TetMesh& releaseWorkspace();
  /// Gives the pages of the vertices and the owner table back on the team's threads: what the
  /// triangulator's destruction would do on one thread. Nothing is read from them afterwards.
  void releasePages();
  /// Ends the vertices: their input point ids, by insertion rank, are written over the start of
  /// the vertex array, 4 bytes each where a record takes 32, so that the output's look-ups stay in
  /// cache and no memory is added. The coordinates and vertex records are gone afterwards.
  const std::uint32_t* packPointIds();

  /// Exhaustive check of the invariants listed in TetMesh.h, of the vertices' records and, unless
  /// a volume threshold was used, of the local Delaunay property. Returns an empty string when all
  /// hold, else one line per violation (the first few of each kind).
  std::string checkMesh() const;

private:
  friend class MeshCheck; // checkMesh(), CheckMesh.cxx
  // Progress is reported (and abort checked) once per this many insertions.
  static constexpr std::size_t kProgressInterval = 1u << 14;
  const double* point(VertId v) const { return mesh_.point(v); }
  std::size_t vertexCount() const { return mesh_.vertices.size(); }

  /// Inserts vertices [begin, end) in the rounds of `roundStarts` (vertex ids); with
  /// `reserveEarly`, once a few rounds tell the tetrahedra per vertex, room for all is made.
  bool insertRounds(std::size_t begin, std::size_t end, const std::vector<std::size_t>& roundStarts,
    bool reserveEarly, const std::function<bool(double)>& progress);
  /// Inserts vertexAt(0), ..., vertexAt(count - 1) with inserter 0, in this thread (a round's
  /// consecutive ranks need no list: its 4 bytes a vertex would add to the peak at the end).
  template <typename VertexAt>
  bool insertSerially(
    std::size_t count, VertexAt vertexAt, const std::function<bool(double)>& progress);
  /// Inserts `vertices` (one BRIO round, in curve order) with every thread: in regions, then in
  /// locking passes, then serially what those could not take; a pass whose kind last yielded too
  /// little to pay for itself is left out. ParallelInsertion.cxx.
  bool insertInParallel(IdArray vertices, const std::function<bool(double)>& progress);
  /// The axis each level of a partition of `vertices` (a round's, ascending) cuts across: from the
  /// mesh's tetrahedra and the points' box.
  std::vector<int> cutAxes(const IdArray& vertices) const;
  /// Each region's points, in the order of `vertices` (the round's curve order), each inserter
  /// restricted to its region from a start in it; the points of a share before the first one that
  /// has a start go to putOff.
  void shareOut(const IdArray& vertices, const Partition& partition,
    std::vector<std::vector<VertId>>& share, std::vector<std::vector<VertId>>& putOff);
  void startInRegion(
    std::size_t k, const Region& region, std::vector<VertId>& share, std::vector<VertId>& putOff);
  /// Inserts `vertices` in the partition's regions, one thread each; returns those that had to be
  /// put off.
  IdArray runRegionPass(const IdArray& vertices, const Partition& partition,
    const std::function<bool(double)>& progress);
  /// The vertices of the lists of `putOff`, in any order, merged into one, ascending, on every
  /// thread: each marks its list's vertices in a flag per rank of `vertices` (ascending), then
  /// each stretch of the flags writes its own. Their count goes to `pass`'s record of points left.
  IdArray mergeAscending(
    const IdArray& vertices, const std::vector<std::vector<VertId>>& putOff, ThreadedWork& pass);
  /// Inserts `vertices` (in curve order), a stretch of them on each of `parts` threads at first
  /// (SharedStretches), each holding the tetrahedra it reads and writes in the owner table;
  /// returns those put off because another thread held a tetrahedron they needed.
  /// ParallelInsertion.cxx.
  IdArray runLockingPass(const IdArray& vertices, std::size_t parts, int pass,
    const std::function<bool(double)>& progress);
  /// The owner table for every slot the mesh has room for, each pool's free slots marked its own.
  void prepareOwners();
  /// Each pool's free slots marked its own in the owner table, or free, each pool on its thread.
  void markFreeSlots(bool owned);
  /// What the calling thread does while the others insert: report progress.
  std::function<void()> progressPoll(const std::function<bool(double)>& progress);
  /// Slots enough for `vertices` vertices in all, from the slots per vertex now and after the
  /// round before (earlierDone_, earlierSlots_), times `margin`.
  std::size_t predictedSlots(std::size_t vertices, double margin) const;
  /// Room in the mesh for `count` more insertions, from the tetrahedra per vertex so far.
  void makeRoomFor(std::size_t count);
  /// More room than there is, for an insertion that found too little.
  void growRecords();
  bool reportProgress(const std::function<bool(double)>& progress);
  /// The predicates' static bound of the power test, for the weights' spread so far.
  void adaptToWeights();
  /// The predicates' tuning widened to `count` more vertices: their grid, and where they lie
  /// beyond the box of those so far, the static bounds of the larger box.
  void tuneFor(const Vertex* more, std::size_t count);

  static constexpr int kLockingPasses = 4;
  static constexpr const char* kLockingPassNames[kLockingPasses] = {"insertion locking pass 1",
    "insertion locking pass 2", "insertion locking pass 3", "insertion locking pass 4"};
  // The fewest points a thread takes in a locking pass (and so the smallest round that goes in
  // parallel, with two threads): its stretch of the curve, far from the others' where they are
  // long, meets them at its ends. 64 insertions cost far more than waking a thread; a larger
  // bound left the small first rounds and what a pass put off to the serial pass.
  static constexpr std::size_t kMinPointsPerThread = 64;
  // Over the slots predicted: the reserve's, made from the first rounds, on all of them; each
  // pass's, made before it, on those it adds. Unwritten slots cost address space only.
  static constexpr double kReserveMargin = 1.15;
  static constexpr double kPassMargin = 1.1;

  Mesh mesh_;
  PeriodicImages images_; // of a periodic mesh's vertices; empty otherwise
  ThreadTeam& team_;
  Predicates tuning_; // adapted to every vertex so far; the inserters take copies
  // The box of every vertex so far, which sets the static bounds: those of the points' own box,
  // not of the frame's, which may hold points far beyond them that come later (a Voronoi run's
  // far points): a bound for those would leave most tests of the first ones to the slower
  // filters, which the power test has no relative one for.
  Bounds staticBox_;
  std::vector<std::unique_ptr<SlotPool>> pools_;
  std::vector<std::unique_ptr<Inserter>> inserters_;
  std::size_t done_ = 0;                           // vertices handled, for progress
  std::size_t earlierDone_ = 0, earlierSlots_ = 0; // done_ and slots after the round before
  std::atomic<std::size_t> passDone_{0};
  std::atomic<bool> stop_{false};
  // Share of its points that the last pass of each kind put in: on some inputs (convex surface
  // samples, whose hull faces run across the whole set) nearly every insertion reaches outside
  // its region, and a pass that puts off most of them only wastes time. A pass left out raises
  // its guess instead (one that put nothing in is not tried again).
  double regionYield_ = 1.0;
  double lockingYield_[kLockingPasses] = {1.0, 1.0, 1.0, 1.0};
  // The locking pass's table, for every slot the records had room for when it was made. Every
  // entry is 0 between passes.
  struct Free
  {
    std::size_t slots;
    void operator()(OwnerTable* p) const { detail::freeBulk(p, slots * sizeof(OwnerTable)); }
  };
  std::unique_ptr<OwnerTable, Free> owners_{nullptr, Free{0}};
  std::size_t ownerSlots_ = 0;
};

template <typename VertexAt>
bool Triangulator::insertSerially(
  std::size_t count, VertexAt vertexAt, const std::function<bool(double)>& progress)
{
  Inserter& inserter = *inserters_[0];
  inserter.unrestricted();
  for (std::size_t i = 0; i < count; ++i)
  {
    if (done_ % kProgressInterval == 0 && !reportProgress(progress))
      return false;
    // Unrestricted, an insertion is put off only when the mesh is full (and a duplicate is done).
    while (inserter.insert(vertexAt(i)) == Inserter::Outcome::Deferred)
      growRecords();
    ++done_;
  }
  return true;
}

} // namespace fd3

#endif
