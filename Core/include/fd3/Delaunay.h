// FastDelaunay3D Core: exact 3D Delaunay tetrahedralization of a point set.
// Plain C++17, no VTK. What a user needs: triangulate(), its Options, the resulting Triangulation
// and its Statistics, and the alpha complex. A distributed or incremental build (the MPI filter's)
// uses fd3/Distributed.h; floating-point measures of simplices are in fd3/Measures.h.
// triangulate() may be called from several threads at once on different inputs; it runs the
// progress callback on the calling thread only.
#ifndef fd3_Delaunay_h
#define fd3_Delaunay_h

#include "fd3/BulkAllocator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fd3
{

/// Order in which points are inserted. Brio (biased randomized insertion order over a Hilbert
/// curve) keeps consecutive points close and the walk short; the others exist for the benchmark.
enum class InsertionOrder
{
  Brio,
  Input,
  Random
};

enum class Status
{
  Ok,
  Empty,        ///< no finite input point
  TooFewPoints, ///< fewer than 4 distinct finite points
  Degenerate,   ///< all distinct points collinear or coplanar: no tetrahedron exists
  Aborted,      ///< the progress callback asked to stop
  CheckFailed,  ///< Options::checkMesh found a broken invariant (a bug): see checkReport
  OutOfRange    ///< the points and box span more than doubles hold: voronoiCells()' vertices,
                ///< triangulatePeriodic()'s images (fd3/Periodic.h); or a weight in a periodic
                ///< box exceeds most by more than (4 periods)^2
};

/// The most threads per hardware thread that Options::threads starts, where that is more than
/// kMinThreadLimit: any count up to that one starts on every machine.
constexpr int kThreadsPerHardwareThread = 4;
constexpr int kMinThreadLimit = 64;

struct Options
{
  /// Target number of points per cell of the background grid (the paper's "onion" search).
  /// 0 disables the grid; the walk then starts from the last created tetrahedron.
  double pointsPerCell = 4.0;
  /// Sliver guard of the paper's core correction: a new tetrahedron whose volume is below this
  /// fraction of the volume of the regular tetrahedron on its longest edge is not created (the core
  /// shrinks instead), except next to the new point's own tetrahedron, where no other choice
  /// exists. The output is then a valid triangulation of the hull, no longer exactly Delaunay.
  /// 0 keeps the output exactly Delaunay.
  double volumeThreshold = 0.0;
  InsertionOrder order = InsertionOrder::Brio;
  std::uint64_t randomSeed = 1;
  /// Points closer than this (in input units) to an already inserted point are skipped and left
  /// unused (vtkDelaunay3D's Tolerance, times the bounding-box diagonal). 0: every distinct point
  /// is a vertex (exact duplicates are always merged).
  double tolerance = 0.0;
  /// Also return the neighbour table. Without it the tetrahedra are compacted in place in the
  /// mesh's own memory, which lowers the peak (the VTK filter does not need neighbours).
  bool computeNeighbors = true;
  /// Called now and then with the fraction of points inserted, always on the thread that called
  /// triangulate() (never on a helper thread); return false to abort.
  std::function<bool(double)> progress;
  /// Check every invariant of the mesh and its local Delaunay property once all points are in
  /// (exact, and as long as the triangulation itself); always on in debug builds.
  bool checkMesh = false;
  /// Threads that insert points; 0: all hardware threads. The output does not depend on it (ties
  /// are broken by a key fixed before insertion). A volume threshold makes the run serial: which
  /// slivers it avoids depends on the order of insertion. At most kThreadsPerHardwareThread per
  /// hardware thread, or kMinThreadLimit where that is more, are started; larger values run as
  /// that many.
  int threads = 1;
  /// A BRIO round is split into one region per thread when it has at least this many points per
  /// thread: smaller regions put off too many insertions at their borders. Smaller rounds go to
  /// the locking passes, which need no regions.
  std::size_t pointsPerThread = 4096;
};

/// Whether none of the point's coordinates is NaN or infinite: the kernel leaves out (and counts,
/// Statistics::nonFinitePoints) every point for which this is false.
inline bool isFinite(const double* p)
{
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// Figures of one run. Times are wall-clock seconds per phase.
struct Statistics
{
  std::size_t inputPoints = 0;
  std::size_t nonFinitePoints = 0;    ///< NaN or Inf coordinates: skipped, left unused
  std::size_t duplicatesMerged = 0;   ///< exact copies of an inserted point: left unused
  std::size_t closePointsSkipped = 0; ///< within Options::tolerance of an inserted point: unused
  std::size_t insertedPoints = 0;     ///< vertices of the triangulation
  /// Weighted points that are no vertex of the regular tetrahedralization (Triangulation::hidden):
  /// an empty power cell, not a lost point.
  std::size_t hiddenPoints = 0;
  std::size_t tetrahedra = 0; ///< finite tetrahedra in the output
  std::size_t walkSteps = 0;  ///< tetrahedra visited by all walks (the paper's "Path")
  std::size_t maxWalkSteps = 0;
  std::size_t cavityTetrahedra = 0; ///< tetrahedra deleted by all insertions
  /// Insertions put off because they reached into another thread's region: each point is
  /// inserted later, in another pass.
  std::size_t deferredInsertions = 0;
  std::size_t exactOrient = 0;   ///< orient3d calls the float filter could not decide
  std::size_t exactInSphere = 0; ///< insphere calls the float filter could not decide
  std::size_t symbolicTies = 0;  ///< insphere ties broken by symbolic perturbation
  /// Exact evaluations in integers of unbounded size: on points whose magnitudes lie too far apart
  /// for one exact scaled frame (Frame::identity), where double expansions would underflow or
  /// overflow. Exact either way; these only cost more.
  std::size_t integerExact = 0;
  double secondsSort = 0, secondsLocate = 0, secondsCavity = 0, secondsFill = 0, secondsOutput = 0;
  double secondsTotal = 0;

  /// The counts and the times, each field listed once: add() sums them, and the MPI filter sums
  /// the counts and takes the slowest rank's times.
  static constexpr std::array<std::size_t Statistics::*, 14> counts()
  {
    return {&Statistics::inputPoints, &Statistics::nonFinitePoints, &Statistics::duplicatesMerged,
      &Statistics::closePointsSkipped, &Statistics::insertedPoints, &Statistics::hiddenPoints,
      &Statistics::tetrahedra, &Statistics::walkSteps, &Statistics::cavityTetrahedra,
      &Statistics::deferredInsertions, &Statistics::exactOrient, &Statistics::exactInSphere,
      &Statistics::symbolicTies, &Statistics::integerExact};
  }
  static constexpr std::array<double Statistics::*, 6> seconds()
  {
    return {&Statistics::secondsSort, &Statistics::secondsLocate, &Statistics::secondsCavity,
      &Statistics::secondsFill, &Statistics::secondsOutput, &Statistics::secondsTotal};
  }

  /// Adds the figures of another part of the same work (a thread's, a batch's): counts and times
  /// are summed, maxWalkSteps is the larger.
  void add(const Statistics& other)
  {
    for (auto field : counts())
      this->*field += other.*field;
    maxWalkSteps = std::max(maxWalkSteps, other.maxWalkSteps);
    for (auto field : seconds())
      this->*field += other.*field;
  }

  double meanWalk() const { return insertedPoints ? double(walkSteps) / insertedPoints : 0.0; }
  double meanCavity() const
  {
    return insertedPoints ? double(cavityTetrahedra) / insertedPoints : 0.0;
  }
};

/// The kernel's arrays of ids: a std::vector whose resize() leaves elements uninitialized
/// (fd3::BulkAllocator).
using IdArray = std::vector<std::uint32_t, BulkAllocator<std::uint32_t>>;

constexpr std::uint32_t kNoNeighbor = 0xFFFFFFFFu; ///< a hull face in Triangulation::neighbors
constexpr std::uint32_t kNoPoint = 0xFFFFFFFFu;    ///< a non-finite point's representative

/// One stretch of work that ran on several threads at once (a parallel insertion pass, a phase
/// on every thread), for a model of how the run scales: what each thread spent on it, by its own
/// CPU clock. Work outside these ran on the calling thread alone.
struct ThreadedWork
{
  const char* phase = "";            ///< "insertion pass 1", "insertion pass 2", ...
  std::vector<double> threadSeconds; ///< each thread's CPU seconds in it; [0]: the calling thread
  /// CPU seconds of the calling thread in it: its own part, and the part of any thread that the
  /// system could not start, which the calling thread then ran.
  double callerSeconds = 0;
  std::size_t points = 0; ///< insertion passes: the points given to the pass
  std::size_t left = 0;   ///< insertion passes: those it put off, to a later pass or the serial one

  /// The longest thread's CPU seconds: what the stretch would take with a core per thread.
  double longest() const
  {
    return threadSeconds.empty() ? 0.0
                                 : *std::max_element(threadSeconds.begin(), threadSeconds.end());
  }
};

struct Triangulation
{
  Status status = Status::Ok;
  /// 4 input point ids per tetrahedron; each tetrahedron is positively oriented:
  /// (p1 - p0) x (p2 - p0) . (p3 - p0) > 0, VTK's VTK_TETRA convention.
  IdArray tetrahedra;
  /// neighbors[4*t + f] = 4*t' + f' where tetrahedron t' shares the face of t opposite its vertex
  /// f, and f' is the vertex of t' opposite that face; kNoNeighbor on the convex hull. Empty unless
  /// Options::computeNeighbors.
  IdArray neighbors;
  /// For each input point: the input id of the vertex it was merged into (exact duplicate) or
  /// skipped for (closer than the tolerance); itself when it is a vertex or hidden; kNoPoint when
  /// not finite. Empty when the status is not Ok.
  IdArray representative;
  /// Weighted points only: the input ids, ascending, of the hidden points, those whose power cell
  /// is empty, so that no tetrahedron has them (a point repeating one merges into it).
  std::vector<std::uint32_t> hidden;
  Statistics stats;
  /// With Status::CheckFailed: what Options::checkMesh found, a line per violation.
  std::string checkReport;
  /// Every stretch of work split over the threads, in the order run (with one thread, the same
  /// stretches, run on the calling thread).
  std::vector<ThreadedWork> threadedWork;

  std::size_t numberOfTetrahedra() const { return tetrahedra.size() / 4; }
};

/// The alpha complex of a Delaunay tetrahedralization, as vtkDelaunay3D defines it: the
/// tetrahedra of circumradius <= alpha; the triangles of circumradius <= alpha that are not a face
/// of those tetrahedra; the edges of half-length <= alpha on neither; the points on none of them.
struct AlphaComplex
{
  IdArray tetrahedra;                   ///< indices into Triangulation::tetrahedra / 4
  std::vector<std::uint32_t> triangles; ///< 3 point ids each
  std::vector<std::uint32_t> lines;     ///< 2 point ids each
  std::vector<std::uint32_t> vertices;  ///< point ids (finite points only)
};

/// Requires `triangulation` to hold neighbours (Options::computeNeighbors). On `threads` threads
/// (0: all hardware threads; bounded as Options::threads), with the same result for any count.
AlphaComplex alphaComplex(const double* xyz, std::size_t count, const Triangulation& triangulation,
  double alpha, int threads = 1);
/// The weighted alpha complex of a regular tetrahedralization (triangulate() with weights): the
/// same, with each simplex's squared circumradius replaced by the squared radius of its smallest
/// orthogonal sphere (negative where the balls overlap enough), compared with alpha^2 as in CGAL's
/// weighted Alpha_shape_3 (whose alpha is that square). Hidden points are in none of it.
AlphaComplex alphaComplex(const double* xyz, const double* weights, std::size_t count,
  const Triangulation& triangulation, double alpha, int threads = 1);

/// The Delaunay tessellation field estimate of the points' density (Schaap and van de Weygaert,
/// 2000), per input point: 4 m / V, where m counts the input points at its vertex (it, and those
/// merged into it) and V is the volume of the tetrahedra around it. The piecewise-linear field
/// through these values integrates over the hull to the number of finite points. A point on the
/// hull has part of a star, so its estimate runs high, as the estimator's does at any boundary.
/// NaN for a point on no tetrahedron (not finite, or a status other than Ok).
std::vector<double> densities(
  const double* xyz, std::size_t count, const Triangulation& triangulation);

/// Delaunay tetrahedralization of `count` points given as x,y,z triples. Throws std::length_error
/// beyond 2^30 points or 2^30 tetrahedra (32-bit ids; about 150M uniform points), std::bad_alloc
/// when memory runs out, and lets exceptions from the progress callback through; all memory is
/// released either way.
/// Exact: every predicate is decided exactly, ties are broken by symbolic perturbation, so the
/// result is a Delaunay triangulation of the distinct finite input points whose boundary is their
/// convex hull.
Triangulation triangulate(const double* xyz, std::size_t count, const Options& options = Options());

/// The regular (weighted Delaunay) tetrahedralization of `count` weighted points: point i at
/// xyz[3i..3i+2] with weight weights[i], its power distance to x being |x - p|^2 - weights[i] (a
/// ball of radius r has weight r^2). It is the Delaunay tetrahedralization where every weight is
/// the same (then computed as such, bit for bit), and any weight, negative too, is allowed. A point
/// of non-finite weight is left out as a non-finite point. A point whose power cell is empty is
/// hidden: no vertex, listed in Triangulation::hidden; of points at one position, only the heaviest
/// can be a vertex. Exact, as triangulate() is, with ties broken by the same symbolic perturbation
/// of the lifted coordinate |p|^2 - w, and the same for any Options::threads.
/// Options::volumeThreshold does not apply (the result is exactly regular).
Triangulation triangulate(
  const double* xyz, const double* weights, std::size_t count, const Options& options = Options());

const char* toString(Status status);

} // namespace fd3

#endif
