// The triangulation's driver: the mesh that every inserter shares, one inserter and one slot pool
// per thread, and the order in which they insert the points: serially for the first BRIO rounds,
// then round by round in parallel (ParallelInsertion.cxx), each thread in a region of its own.
#ifndef fd3_Triangulator_h
#define fd3_Triangulator_h

#include "Geometry.h"
#include "Inserter.h"
#include "fd3/Delaunay.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fd3
{

class Triangulator
{
public:
  /// `vertices` holds the normalized points by insertion rank (vertex id), all distinct, within
  /// `box`; `threads` inserters are made ready.
  Triangulator(VertexArray vertices, const Box& box, const Options& options, int threads);

  /// Inserts every vertex, the rounds of `roundStarts` (first vertex of each BRIO round) after the
  /// first tetrahedron, vertices 0..3. `progress` is called from this thread only; returns false
  /// when it asked to stop.
  bool insertAll(const std::vector<std::size_t>& roundStarts,
    const std::function<bool(double)>& progress);

  /// The figures of every inserter, summed.
  Statistics statistics() const;
  /// Counters of every inserter's predicates, summed.
  void addPredicateCounts(Statistics& stats) const;

  /// Frees the points, the grid and the scratch: only the mesh is left for the output.
  TetMesh& releaseWorkspace();

  /// Exhaustive check of the invariants listed in TetMesh.h, of the vertices' records and, unless
  /// a volume threshold was used, of the local Delaunay property. Returns an empty string when all
  /// hold, else one line per violation (the first few of each kind).
  std::string checkMesh() const;

private:
  // Progress is reported (and abort checked) once per this many insertions.
  static constexpr std::size_t kProgressInterval = 1u << 14;
  const double* point(VertId v) const { return mesh_.point(v); }
  std::size_t vertexCount() const { return mesh_.vertices.size(); }

  /// Inserts `vertices` with inserter 0, in this thread.
  bool insertSerially(const VertId* vertices, std::size_t count, const std::function<bool(double)>& progress);
  /// Inserts `vertices` (one BRIO round, in curve order) with every thread: in regions, twice,
  /// then serially what the regions could not take. ParallelInsertion.cxx.
  bool insertInParallel(std::vector<VertId> vertices, const std::function<bool(double)>& progress);
  /// Inserts `vertices` in `regions`, one thread each; returns those that had to be put off.
  std::vector<VertId> runPass(const std::vector<VertId>& vertices, const std::vector<Region>& regions,
    const std::function<bool(double)>& progress);
  /// Room in the mesh for `count` more insertions, from the tetrahedra per vertex so far.
  void makeRoomFor(std::size_t count);
  bool reportProgress(const std::function<bool(double)>& progress);

  Mesh mesh_;
  std::vector<std::unique_ptr<SlotPool>> pools_;
  std::vector<std::unique_ptr<Inserter>> inserters_;
  std::size_t done_ = 0; // vertices handled, for progress
  std::atomic<std::size_t> passDone_{0};
  std::atomic<bool> stop_{false};
};

} // namespace fd3

#endif
