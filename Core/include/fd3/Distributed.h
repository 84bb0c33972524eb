// FastDelaunay3D Core, distributed and incremental: the exact frame that several pieces of one
// point set (MPI ranks) share, a mesh that points are added to, and the halo each piece sends the
// others. Plain C++17, no VTK; used by the MPI filter.
#ifndef fd3_Distributed_h
#define fd3_Distributed_h

#include "fd3/Bounds.h"
#include "fd3/Delaunay.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace fd3
{

struct ImageOf;         // a periodic image (Core's exact/PeriodicImages.h)
class PeriodicDelaunay; // the periodic driver, which makes meshes of images

/// The exact change of coordinates the kernel computes in, x -> (x - shift) * scale: scale is a
/// power of two and every x - shift is exact, so that every predicate keeps its sign. Every point
/// lies within `bounds`.
struct Frame
{
  double shift[3] = {0, 0, 0};
  double scale = 1.0;
  Bounds bounds;
  /// No shift and no scale (identityFrame()): the points keep magnitudes that no scaled frame
  /// holds exactly, and the predicates work on any finite magnitude (at a higher cost).
  bool identity = false;
};

/// Which coordinates of `count` points can have the centre of `box` subtracted exactly: exact[a] is
/// cleared when one cannot (it is never set, so that several calls, or several MPI ranks, combine
/// by AND).
void checkShifts(const double* xyz, std::size_t count, const Bounds& box, bool exact[3]);
/// The frame for points within `box`, shifted by its centre on the axes where exact (as
/// checkShifts() found for every point) and scaled into [-1, 1].
Frame frameFor(const Bounds& box, const bool exact[3]);
/// Whether `frame` holds each finite one of `count` points exactly, with room for the exact
/// arithmetic of doubles: the image of every coordinate is exact and a multiple of 2^-190, so that
/// no product of five differences underflows. Where it is false for any point (magnitudes far
/// apart: an outlier at 1e100 beside unit data, a cluster 1e-150 wide, a span above DBL_MAX),
/// every piece must use identityFrame() instead.
bool fitsFrame(const Frame& frame, const double* xyz, std::size_t count);
/// The frame that leaves points within `box` as they are (Frame::identity).
Frame identityFrame(const Bounds& box);
/// Whether the finite ones of `count` weights map into `frame` exactly (times the square of its
/// scale, with no overflow or underflow), as a weighted IncrementalDelaunay needs: always in the
/// identity frame.
bool weightsFitFrame(const Frame& frame, const double* weights, std::size_t count);
/// The frame of one whole point set (its finite points), the one that triangulate() uses: every
/// piece of the set computes the same with checkShifts(), frameFor() and fitsFrame() combined
/// over the pieces.
Frame frameOf(const double* xyz, std::size_t count);
/// Coordinates x, y, z of points, in the kernel's allocator: resize() does not zero them, which
/// would touch every page once more before they are filled.
using Coordinates = std::vector<double, BulkAllocator<double>>;

/// What inserting one point changed among a mesh's finite tetrahedra (IncrementalDelaunay::
/// addOne()): the ids of those it deleted and of those it made. A tetrahedron keeps its id while
/// it lives; a deleted one's id goes to a tetrahedron made by a later insertion.
struct MeshChange
{
  std::vector<std::uint32_t> deleted;
  std::vector<std::uint32_t> made;
};

/// A Delaunay tetrahedralization that points can be added to once it is built: the distributed
/// filter inserts the ghost points it receives from other MPI ranks into the mesh of its own.
/// Ids of added points follow the earlier ones. The rules are triangulate()'s, with the figures
/// summed over every batch; Options::tolerance applies to the first batch only. Until there are 4
/// affinely independent points, status() says why (TooFewPoints, Degenerate, Empty) and the mesh
/// keeps the points: the first batch that completes them starts it.
/// A mesh is used by one thread at a time and is not shared between threads; its own threads work
/// inside each call, and the progress callback runs on the calling thread.
class IncrementalDelaunay
{
public:
  /// Tetrahedralizes the first `count` points in `frame`, which must hold every point added later
  /// too (frameFor() over all of them); the caller keeps its points. Throws as triangulate() does.
  /// `room`: about how many points will be added; the kernel's vertex records are reserved for
  /// them (address space, which costs no memory until used), so that add() does not copy the
  /// records of the first ones. With `weights` (one per point, and then with every add()), the
  /// regular tetrahedralization, as triangulate() with weights makes it; every finite weight must
  /// map into the frame exactly (weightsFitFrame()), else std::invalid_argument.
  IncrementalDelaunay(const double* xyz, std::size_t count, const Options& options,
    const Frame& frame, std::size_t room = 0, const double* weights = nullptr);
  /// The same on points that the mesh takes (xyz.size() / 3 of them), and those of every add():
  /// it holds them for points() and release(Coordinates&), except where its vertex records give
  /// them back bit for bit, which it then frees as soon as the records are made, so that they
  /// are not in the peak. The weights it does not take: they are read during the call.
  IncrementalDelaunay(Coordinates xyz, const Options& options, const Frame& frame,
    std::size_t room = 0, const double* weights = nullptr);
  ~IncrementalDelaunay();
  IncrementalDelaunay(const IncrementalDelaunay&) = delete;
  IncrementalDelaunay& operator=(const IncrementalDelaunay&) = delete;

  Status status() const;
  /// The points given so far, every batch's: the ids handed out.
  std::size_t pointCount() const;
  /// Inserts `count` more points, within the frame's box; those that repeat a point are merged
  /// into it as in triangulate(). Throws std::logic_error after an abort, a failed check or
  /// release(), std::invalid_argument for a point outside the frame. A weighted mesh takes the
  /// points' `weights` (std::logic_error without them, or with them on an unweighted one); a
  /// point that repeats a vertex with another weight is then no duplicate: the heavier hides the
  /// other.
  void add(const double* xyz, std::size_t count, const double* weights = nullptr);
  /// add() of one point that reports what it changed, for a caller that keeps a mesh of its own
  /// current (vtkFastDelaunay3D's incremental API): one insertion on the calling thread, its
  /// deleted and made finite tetrahedra in `change`. The point takes the next id, as in add();
  /// returns whether it became a vertex (false: not finite, or a repeat of a vertex, which it is
  /// merged into). Throws as add() does, and std::logic_error while status() is not Ok or on a
  /// weighted mesh.
  bool addOne(const double p[3], MeshChange& change);
  /// The ids of the live finite tetrahedra, for a caller of addOne() that starts its own mesh.
  std::vector<std::uint32_t> liveTetrahedra() const;
  /// The point ids of live tetrahedron t, positively oriented.
  void tetrahedron(std::uint32_t t, std::uint32_t ids[4]) const;

  /// Every point so far, for the finite tetrahedra, neighbours (Options::computeNeighbors),
  /// representatives and figures: a copy, the mesh stays.
  Triangulation snapshot() const;

  /// What triangulate() does with it, without a copy: the output, which ends the mesh.
  Triangulation release();
  /// release() of a mesh that took its points, which gives back the coordinates of every point
  /// so far, as they were given, in `xyz`. Throws std::logic_error for a mesh that did not take
  /// its points.
  Triangulation release(Coordinates& xyz);
  /// For each list of point ids (as haloVertices() gives), their input coordinates, 3 each: as
  /// the mesh holds them or, for a vertex, as its records give them back. Throws
  /// std::invalid_argument for any other id.
  std::vector<std::vector<double>> points(
    const std::vector<std::vector<std::uint32_t>>& lists) const;
  /// The points whose input coordinates the mesh holds (the rest it reads from its records).
  std::size_t heldPoints() const;

  /// haloVertices() of the mesh as it stands, without a snapshot, computed in the frame; `boxes`
  /// in the input's coordinates, and for a weighted mesh `heaviest` too, the largest finite
  /// weight of every piece's points. Empty lists while status() is not Ok.
  std::vector<std::vector<std::uint32_t>> haloVertices(
    const std::vector<Bounds>& boxes, double heaviest = -HUGE_VAL) const;

private:
  friend Triangulation triangulate(
    const double* xyz, const double* weights, std::size_t count, const Options& options);
  friend class PeriodicDelaunay;
  IncrementalDelaunay();
  /// A periodic mesh, which takes its points: each the record of a periodic image, whose exact
  /// coordinates and place in the perturbation's order are in `images` (one per point, residuals
  /// in the input's units), and so for every addImages(). Points with the same record are merged
  /// as repeats, whatever their residuals: the caller tells them apart (mergedPoints(), then
  /// Triangulation::representative). add() inserts points that are no images (the Voronoi
  /// cells' far points). With `weights` (then with every addImages() too), a weighted mesh, as
  /// the constructors make it: points with the same record and another weight are no repeats,
  /// the heavier hiding the lighter.
  static std::unique_ptr<IncrementalDelaunay> ofImages(Coordinates xyz, const ImageOf* images,
    const Options& options, const Frame& frame, const double* weights = nullptr);
  void addImages(
    const double* xyz, const ImageOf* images, std::size_t count, const double* weights = nullptr);
  /// How many points so far were merged into another.
  std::size_t mergedPoints() const;
  /// Calls visit(ids, xyz, weights) for every live finite tetrahedron: its point ids, positively
  /// oriented, its vertices' coordinates in the frame, and for a weighted mesh their weights in
  /// the frame's units (squared lengths; null where unweighted), read where the records are,
  /// not by point id. On the mesh's threads at once: `visit` must be safe to call concurrently.
  void visitTetrahedra(const std::function<void(
      const std::uint32_t ids[4], const double* const xyz[4], const double* weights)>& visit) const;
  /// Calls visit(ids, xyz) for every hull face: its point ids and its vertices' coordinates in
  /// the frame, ordered so that (b - a) x (c - a) points out of the hull. On the mesh's threads
  /// at once, as visitTetrahedra().
  void visitHullFaces(
    const std::function<void(const std::uint32_t ids[3], const double* const xyz[3])>& visit) const;
  /// triangulate()'s mesh: used once, in the frame of its own points, made from their bounds;
  /// weighted where `weights` is given.
  IncrementalDelaunay(
    const double* xyz, const double* weights, std::size_t count, const Options& options);

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
/// The same for a regular tetrahedralization, of points with `weights`: the orthogonal spheres of
/// the tetrahedra take the place of circumspheres, each widened to the power distance of the
/// heaviest point of any piece, `heaviest` (see Halo.cxx for why that is enough). A hidden point
/// is no vertex and is never sent: the whole set hides it too.
std::vector<std::vector<std::uint32_t>> haloVertices(const double* xyz, const double* weights,
  const Triangulation& triangulation, const std::vector<Bounds>& boxes, double heaviest);

} // namespace fd3

#endif
