// FastDelaunay3D Core, periodic: the Delaunay tetrahedralization of a point set repeated along
// some axes of a box (molecular dynamics, granular and cosmological simulation boxes). Plain
// C++17, no VTK.
#ifndef fd3_Periodic_h
#define fd3_Periodic_h

#include "fd3/Bounds.h"
#include "fd3/Delaunay.h"
#include "fd3/Voronoi.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fd3
{

/// The box [lo, hi) on each axis, repeated along the axes where `periodic` is set. The period of
/// an axis is hi - lo; where that difference is no double, its rounding, and the box is then
/// [lo, lo + period).
struct PeriodicBox
{
  double lo[3] = {0, 0, 0};
  double hi[3] = {1, 1, 1};
  bool periodic[3] = {true, true, true};
};

/// The periodic tetrahedralization: every tetrahedron of the repeated points once, up to a
/// translation by whole periods.
struct PeriodicTriangulation
{
  Status status = Status::Ok;
  /// Four input point ids per tetrahedron.
  IdArray tetrahedra;
  /// Three per vertex of each tetrahedron, twelve per tetrahedron: the periods its point, wrapped
  /// into the box (`wraps`), is moved by. The tetrahedron is positive as placed. Its least vertex
  /// (least id, then least offset) has offset 0, so the tetrahedra, each with its least vertex in
  /// the box, fill one period exactly.
  std::vector<std::int8_t> offsets;
  /// Three per input point: the periods subtracted from it to wrap it into the box (0 for a point
  /// in it, or not finite).
  std::vector<std::int32_t> wraps;
  /// Per input point: itself where it is a vertex; else the vertex it repeats once wrapped (an
  /// exact copy, counted in stats.duplicatesMerged) or lies too close to for the doubles to tell
  /// their images apart (an image of each rounds to the same double on every axis, which takes
  /// points within about a unit in the last place of the images' coordinates:
  /// stats.closePointsSkipped); kNoPoint for a point that is not finite (or of a weight that is
  /// not). A hidden point is its own representative, though no vertex.
  IdArray representative;
  /// Weighted points only: the input ids, ascending, of the hidden points, whose power cell in the
  /// repeated set is empty (every image of one is hidden alike); no tetrahedron has them.
  std::vector<std::uint32_t> hidden;
  /// insertedPoints counts the vertices (distinct points less the hidden ones), tetrahedra the
  /// periodic tetrahedra, hiddenPoints the hidden points.
  Statistics stats;
  /// How the tetrahedralization was found: the images of the points inserted around the box, in
  /// a shell of `margin` (input units) on every periodic side and in regions about the spheres
  /// that reached beyond it, after `rounds` rounds that added regions or widened the shell.
  std::size_t imagePoints = 0;
  double margin = 0;
  int rounds = 0;

  std::size_t numberOfTetrahedra() const { return tetrahedra.size() / 4; }
};

/// The Delaunay tetrahedralization of the points (count triples of xyz) repeated along the
/// periodic axes of `box`, exact as triangulate() is: predicates on the exact images (no image
/// p + k L need be a double), ties broken by a perturbation that orders the images by point and
/// then offset, so that a configuration and its translates break them alike. Points outside the
/// box are wrapped into it, exactly. Along axes that are not periodic the points may lie
/// anywhere, and the tetrahedralization ends at the hull of the repeated set (the planes of a
/// slab's highest and lowest points).
///
/// Any number of points works, one included: images of the points around the box are inserted
/// until every tetrahedron at a point of the box provably has its circumsphere within the points
/// present (or the shell is as wide as any such sphere can reach), which also covers the sets too
/// small for a single copy of the box to hold their tetrahedralization.
///
/// Options as for triangulate(), except that tolerance and volumeThreshold are not applied (0:
/// exactly Delaunay, every distinct point a vertex) and no neighbours are given. Throws
/// std::invalid_argument for a box with no periodic axis or a periodic axis with hi <= lo or not
/// finite. Status::OutOfRange where a point lies more than 2^30 periods from the box, an image is
/// no sum of two doubles, or a tetrahedron would span more than 127 periods (a few points in a box
/// thousands of times longer than wide).
PeriodicTriangulation triangulatePeriodic(
  const double* xyz, std::size_t count, const PeriodicBox& box, const Options& options = Options());
/// The regular (weighted Delaunay) tetrahedralization of the weighted points repeated along the
/// periodic axes of `box`, every image of a point with the point's weight: triangulatePeriodic()
/// with the power test (triangulate() with weights), exact and perturbed alike, the images in the
/// same order. Hidden points are no vertices (PeriodicTriangulation::hidden); a point of
/// non-finite weight is left out as one of non-finite coordinates; where every weight is the
/// same, the Delaunay tetrahedralization, bit for bit. A point of weight w reaches sqrt(w - w_0)
/// farther than one of the reference weight w_0 (the 5% quantile of the weights): its images are
/// inserted that much farther out, and Status::OutOfRange where that is more than 4 periods along
/// a periodic axis (each such point would bring thousands of images; CGAL's periodic regular
/// triangulation asks weights below 1/64 of a period squared).
PeriodicTriangulation triangulatePeriodic(const double* xyz, const double* weights,
  std::size_t count, const PeriodicBox& box, const Options& options = Options());

/// The periodic tetrahedra placed as one draws them: each tetrahedron of a PeriodicTriangulation,
/// in its order, with its vertices where its offsets put them, so that together they tile one
/// period. A vertex at its input point's own position keeps the input id; one elsewhere (an image
/// across the box, or an input point outside the box moved into it) is an image point of its own,
/// one per input point and shift however many tetrahedra use it.
struct PeriodicPlacement
{
  /// Four ids per tetrahedron: below the input count, that input point; count + k, image k.
  IdArray tetrahedra;
  /// Per image: the input point it copies.
  std::vector<std::uint32_t> imageSources;
  /// Three per image: the periods it lies from its input point (the vertex's offset less the
  /// point's wraps).
  std::vector<std::int32_t> imageShifts;
  /// x,y,z per image: its input point moved by its shifts times the periods, rounded to doubles.
  std::vector<double> imagePoints;

  std::size_t numberOfImages() const { return imageSources.size(); }
};

/// The tetrahedra of `triangulation` (triangulatePeriodic() of the same points and box) placed:
/// their volumes add up to a period's (for a box periodic on every axis, the box's), up to the
/// rounding of the images' coordinates. Images are numbered in the order the tetrahedra first use
/// them, so the placement is as deterministic as the tetrahedra. A piece's tetrahedra
/// (triangulatePeriodicPiece()) also name its ghosts, after its `count` own points in xyz: those
/// are image points wherever they are.
PeriodicPlacement placePeriodic(const double* xyz, std::size_t count,
  const PeriodicTriangulation& triangulation, const PeriodicBox& box);

/// The periodic Delaunay tessellation field estimate, per input point, as densities() defines it
/// but from each vertex's whole periodic star (`placement` of `triangulation`): no boundary
/// effect along the periodic axes, and the field integrates over one period to the number of
/// finite points. NaN for a point on no tetrahedron.
std::vector<double> densities(const double* xyz, std::size_t count,
  const PeriodicTriangulation& triangulation, const PeriodicPlacement& placement);

/// The alpha complex (alphaComplex() of fd3/Delaunay.h) of the periodic tetrahedralization
/// `placement` places (placePeriodic() of `count` points xyz): tetrahedra as indices into
/// placement.tetrahedra / 4, triangles and lines on the ids of the placement (an input point, or
/// count + an image) of a tetrahedron that holds them, each periodic simplex once; vertices as
/// input ids. Faces and edges are followed across the box. On `threads` threads, the same result
/// for any count. A piece's placement of the stars of its `count` own points (PeriodicPiece::
/// stars) gives every simplex at them as the whole set's gives it; those beyond (of ghosts only,
/// or whose tetrahedra around are not all there) are for another piece to give.
AlphaComplex alphaComplex(const double* xyz, std::size_t count, const PeriodicPlacement& placement,
  double alpha, int threads = 1);
/// The weighted alpha complex of a periodic regular tetrahedralization (triangulatePeriodic()
/// with `weights`, whose PeriodicTriangulation::hidden is `hidden`), as alphaComplex() of
/// fd3/Delaunay.h defines it for weighted points: radii of the smallest orthogonal spheres, every
/// image with its point's weight, hidden points in none of it.
AlphaComplex alphaComplex(const double* xyz, const double* weights, std::size_t count,
  const PeriodicPlacement& placement, const std::vector<std::uint32_t>& hidden, double alpha,
  int threads = 1);

/// The Voronoi cells of the points repeated along the periodic axes of `box`: one per distinct
/// point (as triangulatePeriodic() merges them), around its place in the box, whole along the
/// periodic axes, so that the cells of a box periodic along every axis fill it exactly once;
/// along the others clipped to the box (where it is one there; else to the points' extent). A
/// face's neighbour is the input id of the point across it, also across the box's sides (a
/// point's own image, in a box of few points). options.box and options.generators are not used;
/// threads and progress are as for the tetrahedralization;
/// options.density gives each point the periodic Delaunay tessellation field estimate, from its
/// whole star. Statuses as triangulatePeriodic().
VoronoiCells voronoiCellsPeriodic(
  const double* xyz, std::size_t count, const PeriodicBox& box, const VoronoiOptions& options = {});
/// The power cells of the weighted points repeated along the periodic axes of `box`, as
/// voronoiCellsPeriodic() gives the Voronoi cells, from triangulatePeriodic() with weights. A
/// hidden point's cell is empty (no faces, volume 0), and the cells of a box periodic along every
/// axis still fill it exactly once; densities are NaN at hidden points.
VoronoiCells voronoiCellsPeriodic(const double* xyz, const double* weights, std::size_t count,
  const PeriodicBox& box, const VoronoiOptions& options = {});

/// One piece of a point set spread over several processes by space (the MPI filters' ranks), for
/// the runs of a piece below. The points given to such a run are the piece's own, `own` of them,
/// then its ghosts: every point of the other pieces with an image within `halo` of `region`
/// (periodicImageWithin()). The pieces together give what one process gives the whole set taken
/// in the order of `ids`: each periodic tetrahedron once, by the piece whose own point is its
/// least vertex (least id, then offset 0), and each own point's cell. The predicates and their
/// perturbation do not depend on the ids (PeriodicImages.h), so every piece decides each sign as
/// one process would.
struct PeriodicPiece
{
  std::size_t own = 0;
  /// Per point given, its id in the whole set: which of two repeats is kept, and which piece
  /// takes a tetrahedron, follow them.
  const std::uint32_t* ids = nullptr;
  /// Holds the places of the own points (periodicPlaces()), the same box on every piece that
  /// sends this one its ghosts.
  Bounds region;
  double halo = 0;
  /// Of the whole set: its finite points, and the extent of their places.
  std::size_t points = 0;
  Bounds extent;
  /// Whether the run gives every periodic tetrahedron at an own point, once each, not only those
  /// the piece owns: the stars of its points, which its alpha shape walks
  /// (PeriodicPieceTriangulation::owned).
  bool stars = false;
};

/// Each finite point's place in `box` (its wrap into it, rounded to doubles; see
/// PeriodicTriangulation::wraps), x, y, z, NaN for a point that is not finite: what a piece's own
/// points are chosen by. False where a point lies more than 2^30 periods from the box.
bool periodicPlaces(
  const double* xyz, std::size_t count, const PeriodicBox& box, std::vector<double>& places);

/// Whether an image of a point at `place` (periodicPlaces()) lies within `halo` of `region`, the
/// test that chooses what a piece sends another, widened against the rounding of places.
bool periodicImageWithin(
  const double place[3], const PeriodicBox& box, const Bounds& region, double halo);

/// The first halo of the pieces of `points` finite points whose places span `extent`: a few
/// spacings of evenly spread points, which uniform points need no wider.
double firstPeriodicHalo(const PeriodicBox& box, std::size_t points, const Bounds& extent);

/// A piece's share of triangulatePeriodic() (PeriodicPiece).
struct PeriodicPieceTriangulation
{
  /// The tetrahedra whose least vertex is an own point (with PeriodicPiece::stars, every one at an
  /// own point, and `owned`), on the indices of the points given, as triangulatePeriodic() gives
  /// them; wraps and representative per point given; the statistics count the own points and
  /// the tetrahedra the piece owns.
  PeriodicTriangulation triangulation;
  /// Where asked: per own point, its density as densities() gives it from the whole set (its
  /// star, from every piece's tetrahedra, is within the piece), up to the rounding of the sums.
  /// Rare exceptions, as exact repeats share a place and so a piece: an own point merged into
  /// another piece's point within a rounding of it gets NaN, and that point counts its own mass
  /// only.
  std::vector<double> density;
  /// 0 where the halo was wide enough; else the halo to run again with, once the other pieces
  /// have sent the ghosts within it. Nothing else is set then.
  double widerHalo = 0;
  /// With PeriodicPiece::stars, per tetrahedron: whether the piece owns it.
  std::vector<std::uint8_t> owned;
};

/// The periodic tetrahedra of a piece's points, `count` of them, own then ghosts (PeriodicPiece),
/// with their densities where `density`. Statuses and throws as triangulatePeriodic().
PeriodicPieceTriangulation triangulatePeriodicPiece(const double* xyz, std::size_t count,
  const PeriodicBox& box, const PeriodicPiece& piece, bool density,
  const Options& options = Options());

/// The cells of a piece's own points, as voronoiCellsPeriodic() gives them of the whole set
/// (generators and neighbours as indices of the points given). `widerHalo` as in
/// PeriodicPieceTriangulation; there are no cells where it is not 0.
VoronoiCells voronoiCellsPeriodicPiece(const double* xyz, std::size_t count, const PeriodicBox& box,
  const PeriodicPiece& piece, double& widerHalo, const VoronoiOptions& options = {});

} // namespace fd3

#endif
