// FastDelaunay3D Core: exact 3D Delaunay tetrahedralization of a point set.
// Plain C++17, no VTK. The only public header of the kernel.
#ifndef fd3_Delaunay_h
#define fd3_Delaunay_h

#include "fd3/BulkAllocator.h"

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

/// Order in which points are inserted. Brio (biased randomized insertion order over a Hilbert curve)
/// keeps consecutive points close and the walk short; the others exist for the benchmark.
enum class InsertionOrder
{
  Brio,
  Input,
  Random
};

enum class Status
{
  Ok,
  Empty,          ///< no finite input point
  TooFewPoints,   ///< fewer than 4 distinct finite points
  Degenerate,     ///< all distinct points collinear or coplanar: no tetrahedron exists
  Aborted,        ///< the progress callback asked to stop
  CheckFailed     ///< Options::checkMesh found a broken invariant (a bug): see checkReport
};

/// The most threads per hardware thread that Options::threads starts.
constexpr int kThreadsPerHardwareThread = 4;

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
  /// Called now and then with the fraction of points inserted; return false to abort.
  std::function<bool(double)> progress;
  /// Check every invariant of the mesh and its local Delaunay property once all points are in
  /// (exact, and as long as the triangulation itself); always on in debug builds.
  bool checkMesh = false;
  /// Threads that insert points; 0: all hardware threads. The output does not depend on it (ties
  /// are broken by a key fixed before insertion). A volume threshold makes the run serial: which
  /// slivers it avoids depends on the order of insertion. At most kThreadsPerHardwareThread per
  /// hardware thread are started; larger values run as that many.
  int threads = 1;
  /// A BRIO round goes in parallel when it has at least this many points per thread (smaller
  /// ones do not repay the threads' start and the regions' borders).
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
  std::size_t nonFinitePoints = 0;     ///< NaN or Inf coordinates: skipped, left unused
  std::size_t duplicatesMerged = 0;    ///< exact copies of an inserted point: left unused
  std::size_t closePointsSkipped = 0;  ///< within Options::tolerance of an inserted point: unused
  std::size_t insertedPoints = 0;      ///< vertices of the triangulation
  std::size_t tetrahedra = 0;          ///< finite tetrahedra in the output
  std::size_t walkSteps = 0;           ///< tetrahedra visited by all walks (the paper's "Path")
  std::size_t maxWalkSteps = 0;
  std::size_t cavityTetrahedra = 0;    ///< tetrahedra deleted by all insertions
  /// Insertions put off because they reached into another thread's region: each point is
  /// inserted later, in another pass.
  std::size_t deferredInsertions = 0;
  std::size_t exactOrient = 0;         ///< orient3d calls the float filter could not decide
  std::size_t exactInSphere = 0;       ///< insphere calls the float filter could not decide
  std::size_t symbolicTies = 0;        ///< insphere ties broken by symbolic perturbation
  /// Exact evaluations in integers of unbounded size: on points whose magnitudes lie too far apart
  /// for one exact scaled frame (Frame::identity), where double expansions would underflow or
  /// overflow. Exact either way; these only cost more.
  std::size_t integerExact = 0;
  double secondsSort = 0, secondsLocate = 0, secondsCavity = 0, secondsFill = 0, secondsOutput = 0;
  double secondsTotal = 0;

  double meanWalk() const { return insertedPoints ? double(walkSteps) / insertedPoints : 0.0; }
  double meanCavity() const { return insertedPoints ? double(cavityTetrahedra) / insertedPoints : 0.0; }
};

/// The kernel's arrays of ids: a std::vector whose resize() leaves elements uninitialized (fd3::BulkAllocator).
using IdArray = std::vector<std::uint32_t, BulkAllocator<std::uint32_t>>;

constexpr std::uint32_t kNoNeighbor = 0xFFFFFFFFu; ///< a hull face in Triangulation::neighbors
constexpr std::uint32_t kNoPoint = 0xFFFFFFFFu;    ///< a non-finite point's representative

struct Triangulation
{
  Status status = Status::Ok;
  /// 4 input point ids per tetrahedron; each tetrahedron is positively oriented:
  /// (p1 - p0) x (p2 - p0) . (p3 - p0) > 0, VTK's VTK_TETRA convention.
  IdArray tetrahedra;
  /// neighbors[4*t + f] = 4*t' + f' where tetrahedron t' shares the face of t opposite its vertex f,
  /// and f' is the vertex of t' opposite that face; kNoNeighbor on the convex hull.
  /// Empty unless Options::computeNeighbors.
  IdArray neighbors;
  /// For each input point: the input id of the vertex it was merged into (exact duplicate) or
  /// skipped for (closer than the tolerance); itself when it is a vertex; kNoPoint when not finite.
  /// Empty when the status is not Ok.
  std::vector<std::uint32_t> representative;
  Statistics stats;
  /// With Status::CheckFailed: what Options::checkMesh found, a line per violation.
  std::string checkReport;

  std::size_t numberOfTetrahedra() const { return tetrahedra.size() / 4; }
};

/// The alpha complex of a Delaunay tetrahedralization, as vtkDelaunay3D defines it: the
/// tetrahedra of circumradius <= alpha; the triangles of circumradius <= alpha that are not a face of
/// those tetrahedra; the edges of half-length <= alpha on neither; the points on none of them.
struct AlphaComplex
{
  IdArray tetrahedra; ///< indices into Triangulation::tetrahedra / 4
  std::vector<std::uint32_t> triangles;  ///< 3 point ids each
  std::vector<std::uint32_t> lines;      ///< 2 point ids each
  std::vector<std::uint32_t> vertices;   ///< point ids (finite points only)
};

/// Requires `triangulation` to hold neighbours (Options::computeNeighbors).
AlphaComplex alphaComplex(
  const double* xyz, std::size_t count, const Triangulation& triangulation, double alpha);

/// Delaunay tetrahedralization of `count` points given as x,y,z triples. Throws std::length_error
/// beyond 2^30 points or 2^30 tetrahedra (32-bit ids; about 150M uniform points), std::bad_alloc
/// when memory runs out, and lets exceptions from the progress callback through; all memory is
/// released either way.
/// Exact: every predicate is decided exactly, ties are broken by symbolic perturbation, so the result
/// is a Delaunay triangulation of the distinct finite input points whose boundary is their convex hull.
Triangulation triangulate(const double* xyz, std::size_t count, const Options& options = Options());

/// An axis-aligned box {xmin, xmax, ymin, ymax, zmin, zmax}, as VTK writes bounds; xmin > xmax
/// is an empty box.
using Bounds = std::array<double, 6>;

/// The exact change of coordinates the kernel computes in, x -> (x - shift) * scale: scale is a
/// power of two and every x - shift is exact, so that every predicate keeps its sign. Every point
/// lies within [lo, hi].
struct Frame
{
  double shift[3] = {0, 0, 0};
  double scale = 1.0;
  double lo[3] = {0, 0, 0};
  double hi[3] = {0, 0, 0};
  /// No shift and no scale (identityFrame()): the points keep magnitudes that no scaled frame
  /// holds exactly, and the predicates work on any finite magnitude (at a higher cost).
  bool identity = false;
};

/// Which coordinates of `count` points can have `centre` subtracted exactly: exact[a] is cleared
/// when one cannot (it is never set, so that several calls, or several MPI ranks, combine by AND).
void checkShifts(const double* xyz, std::size_t count, const double centre[3], bool exact[3]);
/// The frame for points within [lo, hi], shifted by the box's centre on the axes where exact (as
/// checkShifts() found for every point) and scaled into [-1, 1].
Frame frameFor(const double lo[3], const double hi[3], const bool exact[3]);
/// Whether `frame` holds each finite one of `count` points exactly, with room for the exact
/// arithmetic of doubles: the image of every coordinate is exact and a multiple of 2^-190, so that
/// no product of five differences underflows. Where it is false for any point (magnitudes far
/// apart: an outlier at 1e100 beside unit data, a cluster 1e-150 wide, a span above DBL_MAX),
/// every piece must use identityFrame() instead.
bool fitsFrame(const Frame& frame, const double* xyz, std::size_t count);
/// The frame that leaves points within [lo, hi] as they are (Frame::identity).
Frame identityFrame(const double lo[3], const double hi[3]);
/// Whether the kernel's records of `count` points in `frame` give each finite one back bit for bit
/// (Tetrahedralization::points(), release(xyz)): every coordinate maps into the frame and back
/// exactly (no underflow), and none is -0, which an exact duplicate at +0 would come back as.
bool recoverable(const Frame& frame, const double* xyz, std::size_t count);

/// A Delaunay tetrahedralization that points can be added to once it is built: the distributed
/// filter inserts the ghost points it receives from other MPI ranks, round after round, into one
/// mesh. Ids of added points follow the earlier ones. The rules are triangulate()'s, with the
/// figures summed over every batch; Options::tolerance applies to the first batch only.
/// Until there are 4 affinely independent points, status() says why (TooFewPoints, Degenerate,
/// Empty) and the points are kept: the first batch that completes them starts the mesh.
class Tetrahedralization
{
public:
  /// Tetrahedralizes the first `count` points in `frame`, which must hold every point added later
  /// too (frameFor() over all of them). Throws as triangulate() does. `room`: about how many points
  /// will be added; the kernel's vertex records are reserved for them (address space, which costs
  /// no memory until used), so that add() does not copy the records of the first ones.
  /// `pointsRead`: called once the points are in the vertex records, before they are inserted (not
  /// when the mesh cannot start yet): a caller whose points are recoverable() can free its copy
  /// there, and have them back from points() and release(xyz), so that they are not in the peak.
  Tetrahedralization(const double* xyz, std::size_t count, const Options& options, const Frame& frame,
    std::size_t room = 0, const std::function<void()>& pointsRead = nullptr);
  ~Tetrahedralization();
  Tetrahedralization(const Tetrahedralization&) = delete;
  Tetrahedralization& operator=(const Tetrahedralization&) = delete;

  Status status() const;
  /// Inserts `count` more points, within the frame's box; those that repeat a point are merged
  /// into it as in triangulate(). Throws std::logic_error after an abort, a failed check or
  /// release(), std::invalid_argument for a point outside the frame.
  void add(const double* xyz, std::size_t count);
  /// Every point so far, for the finite tetrahedra, neighbours (Options::computeNeighbors),
  /// representatives and figures: a copy, the mesh stays.
  Triangulation snapshot() const;

  /// What triangulate() does with it, without a copy: the output, which ends the mesh.
  Triangulation release();
  /// release(), which also writes the input coordinates of every vertex and of every exact
  /// duplicate to xyz[3 * id], as the records give them back (exactly for recoverable() points),
  /// once the tetrahedra are compacted: the records of half their size are given back by then.
  /// Other points (not finite, skipped for the tolerance) are left as they are.
  Triangulation release(double* xyz);
  /// For each list of vertices (point ids, as haloVertices() gives), their input coordinates, 3
  /// each, as the records give them back. Throws std::invalid_argument for an id that is not a
  /// vertex.
  std::vector<std::vector<double>> points(const std::vector<std::vector<std::uint32_t>>& lists) const;

  /// haloVertices() of the mesh as it stands, without a snapshot, computed in the frame; `boxes`
  /// in the input's coordinates. Empty lists while status() is not Ok.
  std::vector<std::vector<std::uint32_t>> haloVertices(const std::vector<Bounds>& boxes) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// For a point set split into pieces (MPI ranks), what this piece must send to the piece of each
/// box so that the Delaunay tetrahedra of the whole set that touch that piece's points are all in
/// the tetrahedralization of its points plus the ones received: for each box, the vertices of the
/// tetrahedra whose circumsphere meets the box and of the hull faces whose outer half-space meets
/// it (widened, never narrowed, against rounding). One exchange is enough (Funke and Sanders,
/// 2017). Requires neighbours; a piece whose points have no tetrahedron sends them all instead.
std::vector<std::vector<std::uint32_t>> haloVertices(
  const double* xyz, const Triangulation& triangulation, const std::vector<Bounds>& boxes);

const char* toString(Status status);

} // namespace fd3

#endif
