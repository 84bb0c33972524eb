// The periodic tetrahedralization (fd3/Periodic.h) from the ordinary one of a covering: the points
// wrapped into the box, and their images in a shell around it, inserted into one mesh whose
// predicates decide the exact images (PeriodicImages.h). Images are added until a certificate
// holds: every tetrahedron with a vertex in the box has its circumsphere, where it meets the
// points' extent along the axes that are not periodic, inside the shell or inside one region
// whose images are all present, so that no point missing from the covering could lie in it (and
// the hull faces there are a slab's, parallel to the periods). Those tetrahedra are then exactly
// the periodic ones at the box's points (their stars are complete), and each periodic tetrahedron
// is taken once, by the copy whose least vertex lies in the box. The regions are the failed
// spheres' (and the outer sides of the failed hull faces, first; ImageRegion.h): a slab's
// tetrahedra under its highest and lowest planes reach a period across, but only as thin caps,
// whose few points' images a region adds where a wider shell would add every point's. After a
// few such rounds the shell widens all round instead.
//
// A shell of width m* = h + sqrt(h^2 + H^2) needs no certificate, h being half the diagonal of a
// period and H the diagonal of the points' extent along the axes that are not periodic: the
// circumcentre c of a tetrahedron at point p lies in p's cell, within h of p along the periodic
// axes (p's own images bound it), and its sphere meets the points' extent within
// sqrt(h^2 + H^2) of c there, or it would hold an image of every point, a whole period, inside.
//
// Weighted points (power distance |x - p|^2 - w) make the covering a regular tetrahedralization.
// An image q conflicts with an orthosphere (c, r) only where |q - c|^2 < r^2 + w_q, so within
// R + sqrt(max(w_q - w_0, 0)) of c, R^2 = r^2 + w_0 for a reference weight w_0 (roots add up no
// less). So each point's images are held a reach sqrt(max(w - w_0, 0)) beyond the shell and the
// regions, and the certificate checks the balls (c, R) where it checked circumspheres: a heavy
// point brings its images from afar, not every point's. w_0 is a low quantile of the weights. The orthocentre of a tetrahedron at p lies in p's power
// cell, which p's images (of p's weight) bound as they bound its Voronoi cell, and R is at most
// the distance to the nearest image of a point of weight w_0 or more, so the widest shell is the
// same. A point that the covering
// hides is hidden in the repeated set, whose points include the covering's; the covering keeps
// every point that the repeated set keeps, whose stars it certifies.
//
// A piece (PeriodicPiece, an MPI rank's share) has its own points in place of the box's, and its
// region and halo in place of the box and the shell: its covering is its points and every image
// within the halo of its region, the certificate is the same about the region, and where it
// fails the piece cannot add images it does not have, so it asks for a wider halo instead.
#ifndef fd3_PeriodicDelaunay_h
#define fd3_PeriodicDelaunay_h

#include "exact/PeriodicImages.h"
#include "fd3/Distributed.h"
#include "fd3/Periodic.h"
#include "fd3/Voronoi.h"
#include "periodic/Buckets.h"
#include "periodic/ImageRegion.h"

#include <array>
#include <cstdint>
#include <memory>
#include <unordered_set>
#include <vector>

namespace fd3
{

class PeriodicDelaunay
{
public:
  /// Throws std::invalid_argument for a box with no periodic axis, or a periodic axis with
  /// hi <= lo or not finite. With `weights` (one per point, read during the calls), the regular
  /// tetrahedralization and power cells.
  PeriodicDelaunay(const double* xyz, const double* weights, std::size_t count,
    const PeriodicBox& box, const Options& options);
  /// The same for a piece of the points (PeriodicPiece), whose own points take the place of the
  /// box's, and whose region and halo take the place of the box and the shell.
  PeriodicDelaunay(const double* xyz, std::size_t count, const PeriodicBox& box,
    const Options& options, const PeriodicPiece& piece);
  /// The tetrahedralization; with `density`, the densities of the box's points (a piece's own),
  /// from the covering's tetrahedra at them.
  PeriodicTriangulation run(std::vector<double>* density = nullptr);
  /// The cells of the box's points (voronoiCellsPeriodic()).
  VoronoiCells cells(const VoronoiOptions& options);
  /// A piece's: 0 where its halo was wide enough for run() or cells(), else the halo to try next.
  double widerHalo() const { return widerHalo_; }
  /// A piece's run() with PeriodicPiece::stars: whether it owns each of its tetrahedra.
  std::vector<std::uint8_t>& owned() { return owned_; }
  /// The places of the points (periodicPlaces()); false where one lies too far.
  bool places(std::vector<double>& out);
  /// The first shell's width, were there `points` points spanning `extent` (firstPeriodicHalo()).
  static double firstShell(const PeriodicBox& box, std::size_t points, const Bounds& extent);

private:
  /// A point of the covering: the image of input point `owner` (a vertex of the box), moved by
  /// `offset` periods from the owner's place in the box.
  struct CoveringPoint
  {
    std::uint32_t owner;
    std::array<std::int8_t, 3> offset;
  };

  /// Wraps the points and chooses the frame: OutOfRange where a point lies too far, Empty where
  /// none is finite, else Ok; `stats` gets the points counted so far.
  Status prepare(Statistics& stats);
  /// The points' figures: input, not finite, repeats, too close, and those of the box.
  void countPoints(Statistics& stats) const;
  /// Wraps every finite point (of finite weight) into the box (wraps, and each one's exact place),
  /// each a point of the box until its images show it repeats another; false where one lies too
  /// far. Weights that are all the same are dropped: the Delaunay tetrahedralization, bit for bit.
  bool wrapPoints();
  /// The frame of the covering at its widest: the box and the widest shell, or the points'
  /// extent along the axes that are not periodic.
  void chooseFrame();
  /// Room in the covering's lists for the box's points and the first shell's images.
  void reserveCovering();
  /// Appends the box's points, each at its place (offset 0).
  void addPoints();
  /// Appends the images of the box's points within `outer` of the box and not within `inner`
  /// (none for inner < 0), the points themselves left out; false where an image is no sum of two
  /// doubles.
  bool addShell(double inner, double outer);
  /// The covering's mesh, shell by shell until the certificate holds; null where an image is no
  /// sum of two doubles.
  std::unique_ptr<IncrementalDelaunay> cover(PeriodicTriangulation& out);
  /// The points whose images the mesh merged into another's, which share their records: repeats
  /// of a place, and points within a rounding of another, whose images the covering then lacks.
  /// Each gets the earlier point as its representative; returns whether any was too close, to
  /// build again without it.
  bool resolveMerged(const Triangulation& covering);
  /// Where the certificate fails: the regions (input units) whose images the covering lacks,
  /// each within the widest shell. `hull`: about the hull faces at points of the box that are
  /// not parallel to the periods, on their outer side. `spheres`: about the spheres of
  /// tetrahedra at points of the box that reach beyond the shell and every region so far (where
  /// they meet the points' extent along the free axes), and about tetrahedra flat in floats.
  struct Failures
  {
    std::vector<ImageRegion> hull, spheres;
    /// Where every axis is periodic, the hull faces instead: a, b, c (input units), ordered so
    /// that (b - a) x (c - a) points out (outerBall()).
    std::vector<std::array<double, 9>> outerFaces;
  };
  Failures failures(const IncrementalDelaunay& mesh) const;
  /// A piece's halo after a covering whose certificate failed as `failed` says: wide enough for
  /// the failed spheres, and wider than the last, up to the widest shell; 0 where none failed.
  double widerHaloFor(const Failures& failed) const;
  /// Where every axis is periodic, the region of a hull face of the covering (Failures::
  /// outerFaces): the images on the face's outer side within the sphere through the face and an
  /// image beyond it, a spacing wider: of the images tried, the one whose sphere has the lowest
  /// centre. They are one period outwards along an axis, of the face's vertices and of the points
  /// across its circle. The repeated set's tetrahedron beyond the face has a sphere through the
  /// face that leaves every image out, so a centre lower still, and the outer caps of the spheres
  /// through a circle grow with their centre's height: its fourth vertex is in the region. So is
  /// the image found, and the face is no hull face once the region's images are in. A box a
  /// period wide each way, as where some axis is not periodic, would hold nine periods' images:
  /// a slab's whole thickness, across a vacuum.
  ImageRegion outerBall(const std::array<double, 9>& face);
  /// Where they outnumber the points, the failed spheres' balls snapped out to a lattice of
  /// kSnap spacings, centres to its nodes and radii to its steps, each kept once; the other
  /// regions, or all of them, as they are. Across a gap between planes spheres fail by the
  /// hundred thousand, four a point, nearly alike, and each region costs a pass over the buckets
  /// it overlaps; elsewhere (a vacuum, clusters) they are fewer, and a lattice adds more images
  /// than it saves passes.
  std::vector<ImageRegion> coarsened(const std::vector<ImageRegion>& regions) const;
  /// Appends the images inside `regions` that the covering lacks, and keeps the regions: every
  /// image in them is then present. False where an image is out of range.
  bool addRegions(const std::vector<ImageRegion>& regions);
  /// Files the box's points by place (pointBuckets_, places_).
  void filePoints();
  /// Whether point id, moved by `shift` periods, lies in `region` (weighted, within its reach
  /// of it: reachOf()).
  bool inRegion(std::uint32_t id, const int shift[3], const ImageRegion& region) const;
  /// Appends that image where the covering lacks it (true where it has it); false where it is no
  /// sum of two doubles.
  bool addRegionImage(std::uint32_t id, const int shift[3]);
  /// Appends the image of point id moved by offset o (and its weight); false where it is no sum
  /// of two doubles.
  bool addImage(std::uint32_t id, const std::array<std::int8_t, 3>& o);
  /// Whether that image lies within `margin` of the box along every periodic axis (weighted,
  /// `margin` and its reach).
  bool inShell(std::uint32_t id, const std::array<std::int8_t, 3>& o, double margin) const;
  static std::uint64_t keyOf(std::uint32_t id, const std::array<std::int8_t, 3>& o)
  {
    return std::uint64_t(id) << 24 | std::uint64_t(std::uint8_t(o[0])) << 16 |
      std::uint64_t(std::uint8_t(o[1])) << 8 | std::uint64_t(std::uint8_t(o[2]));
  }
  /// How far beyond the shell and the regions the images of weighted point id are held:
  /// sqrt(max(w - w_0, 0)), w_0 the reference weight (the class documentation).
  double reachOf(std::uint32_t id) const
  {
    return weights_ ? std::sqrt(std::max(weights_[id] - referenceWeight_, 0.0)) : 0.0;
  }
  /// Whether a weighted point reaches more than kMostReach periods.
  bool reachesTooFar() const;
  /// A point's id in the whole set: a piece's ids, else its index.
  std::uint32_t idOf(std::uint32_t point) const { return ids_ ? ids_[point] : point; }
  /// The covering points in the order that picks each periodic tetrahedron's copy: by the id of
  /// the point kept for the owner, then by offset, lexicographic. Translating a tetrahedron keeps
  /// the order of its vertices.
  std::uint64_t rankOf(const CoveringPoint& p) const
  {
    const std::uint32_t kept = merged_ ? representative_[p.owner] : p.owner;
    return std::uint64_t(idOf(kept)) << 24 | std::uint64_t(p.offset[0] + 128) << 16 |
      std::uint64_t(p.offset[1] + 128) << 8 | std::uint64_t(p.offset[2] + 128);
  }
  /// Which of the covering tetrahedron v's vertices comes first in rankOf()'s order.
  int leastVertex(const std::uint32_t v[4]) const
  {
    int least = 0;
    std::uint64_t first = rankOf(covering_[v[0]]);
    for (int i = 1; i < 4; ++i)
      if (const std::uint64_t rank = rankOf(covering_[v[i]]); rank < first)
      {
        first = rank;
        least = i;
      }
    return least;
  }
  /// Point id's place moved by `periods` along axis k, in floats (only 0 along an axis that is
  /// not periodic, whose period may be no number).
  double shifted(std::uint32_t id, int k, int periods) const
  {
    return periods == 0 ? place_[id][k] : place_[id][k] + periods * period_[k];
  }
  /// Calls visit(id) for the box's points, then for a piece's ghosts.
  template <typename Visit>
  void forEachPoint(Visit&& visit) const
  {
    for (const std::uint32_t id : points_)
      visit(id);
    for (const std::uint32_t id : ghosts_)
      visit(id);
  }
  /// Whether the hull face (a, b, c) of covering points is parallel to every periodic axis,
  /// exactly.
  bool parallelToPeriods(const std::uint32_t face[3]) const;
  void extract(const Triangulation& covering, PeriodicTriangulation& out) const;
  /// The box's points that the covering hides, ascending (PeriodicTriangulation::hidden).
  std::vector<std::uint32_t> hiddenOfBox(const Triangulation& covering) const;
  /// A piece's extract() with PeriodicPiece::stars: every periodic tetrahedron at an own point,
  /// as the copy at its least vertex, once, and owned_; false where a copy spans more periods
  /// than the offsets' bytes hold.
  bool extractStars(const Triangulation& covering, PeriodicTriangulation& out);
  /// Per box point (a piece's own), densities() from the covering's tetrahedra at it: each
  /// periodic tetrahedron at a point has one copy at its place, whatever copy takes it.
  std::vector<double> densitiesOfBoxPoints(const Triangulation& covering) const;

  const double* xyz_;
  // Null where unweighted, or where every finite point has the same weight; then the largest
  // finite weight less the smallest, the reference weight and the largest reachOf().
  const double* weights_;
  double weightSpread_ = 0, referenceWeight_ = 0, farthestReach_ = 0;
  std::size_t count_;
  // The points whose tetrahedra and cells are made, the first ones: all of them, or a piece's
  // own; and a piece's ids.
  std::size_t own_;
  const std::uint32_t* ids_ = nullptr;
  PeriodicBox box_;
  // Where the box's points lie, about which the shell is: the box along the periodic axes and
  // everywhere along the others, or a piece's region. Its points' extent, or the whole set's.
  Bounds region_, extent_;
  bool piece_ = false, stars_ = false;
  std::vector<std::uint8_t> owned_;
  double pieceHalo_ = 0;
  std::size_t pieceSetPoints_ = 0;
  double widerHalo_ = 0;
  Options options_;
  double period_[3];
  int periodicAxes_ = 0;
  double widest_ = 0;  // m*
  double spacing_ = 0; // of the points, were they spread evenly
  double margin_ = 0;  // the shell's width so far
  Frame frame_;
  // The covering's points at the widest shell, and the cells' clipping box (cells()): the frame
  // holds both, and the far points about them.
  Bounds coverBounds_, clipBox_;
  // By input point: its place in the box (the rounding and the residual), its key, and what
  // represents it.
  std::vector<std::array<double, 3>> place_, placeResidual_;
  std::vector<std::int32_t> wraps_;
  std::vector<std::uint32_t> representative_;
  bool merged_ = false;               // whether any point has another as its representative
  std::vector<std::uint32_t> points_; // the box's points: the representatives of themselves
  std::vector<std::uint32_t> ghosts_; // a piece's other points, each its own representative
  std::size_t duplicates_ = 0, close_ = 0, nonFinite_ = 0;
  // The covering, batch after batch: its records (input units), images, and what each point is.
  std::vector<double> coveringXyz_;
  std::vector<ImageOf> coveringImages_;
  std::vector<double> coveringWeights_; // weighted only
  std::vector<CoveringPoint> covering_;
  // The covering's first points, its points of the box (offset 0): each id below it is one.
  std::uint32_t boxPoints_ = 0;
  // Beyond the shell, the regions whose images are all present, and those images (keyOf()).
  std::vector<ImageRegion> regions_;
  std::unordered_set<std::uint64_t> present_;
  // The box's points by place, for the images in a region, and the extent of their places.
  std::unique_ptr<Buckets> pointBuckets_;
  Bounds places_;
};

} // namespace fd3

#endif
