// FastDelaunay3D Core, distributed and incremental: the exact frame that several pieces of one
// point set (MPI ranks) share, a mesh that points are added to, and the halo each piece sends the
// others. Plain C++17, no VTK; used by the MPI filter.
#ifndef fd3_Distributed_h
#define fd3_Distributed_h

#include "fd3/Delaunay.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace fd3
{

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

/// Which coordinates of `count` points can have the centre of the box [lo, hi] subtracted exactly:
/// exact[a] is cleared when one cannot (it is never set, so that several calls, or several MPI
/// ranks, combine by AND).
void checkShifts(
  const double* xyz, std::size_t count, const double lo[3], const double hi[3], bool exact[3]);
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
/// The frame of one whole point set (its finite points), the one that triangulate() uses: every
/// piece of the set computes the same with checkShifts(), frameFor() and fitsFrame() combined
/// over the pieces.
Frame frameOf(const double* xyz, std::size_t count);
/// Whether the kernel's records of `count` points in `frame` give each finite one back bit for bit
/// (IncrementalDelaunay::points(), release(xyz)): every coordinate maps into the frame and back
/// exactly (no underflow), and none is -0, which an exact duplicate at +0 would come back as.
bool recoverable(const Frame& frame, const double* xyz, std::size_t count);

/// A Delaunay tetrahedralization that points can be added to once it is built: the distributed
/// filter inserts the ghost points it receives from other MPI ranks, round after round, into one
/// mesh. One thread uses a mesh at a time (its own threads work inside each call). Ids of added points follow the earlier ones. The rules are triangulate()'s, with the
/// figures summed over every batch; Options::tolerance applies to the first batch only.
/// Until there are 4 affinely independent points, status() says why (TooFewPoints, Degenerate,
/// Empty) and the points are kept: the first batch that completes them starts the mesh.
class IncrementalDelaunay
{
public:
  /// Tetrahedralizes the first `count` points in `frame`, which must hold every point added later
  /// too (frameFor() over all of them). Throws as triangulate() does. `room`: about how many points
  /// will be added; the kernel's vertex records are reserved for them (address space, which costs
  /// no memory until used), so that add() does not copy the records of the first ones.
  /// `pointsRead`: called once the points are in the vertex records, before they are inserted (not
  /// when the mesh cannot start yet): a caller whose points are recoverable() can free its copy
  /// there, and have them back from points() and release(xyz), so that they are not in the peak.
  IncrementalDelaunay(const double* xyz, std::size_t count, const Options& options,
    const Frame& frame, std::size_t room = 0, const std::function<void()>& pointsRead = nullptr);
  ~IncrementalDelaunay();
  IncrementalDelaunay(const IncrementalDelaunay&) = delete;
  IncrementalDelaunay& operator=(const IncrementalDelaunay&) = delete;

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
  std::vector<std::vector<double>> points(
    const std::vector<std::vector<std::uint32_t>>& lists) const;

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

} // namespace fd3

#endif
