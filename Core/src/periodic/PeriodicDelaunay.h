// The periodic tetrahedralization (fd3/Periodic.h) from the ordinary one of a covering: the points
// wrapped into the box, and their images in a shell around it, inserted into one mesh whose
// predicates decide the exact images (PeriodicImages.h). The shell widens until a certificate
// holds: every tetrahedron with a vertex in the box has its circumsphere, where it meets the
// points' extent along the axes that are not periodic, inside the shell, so that no point missing
// from the covering could lie in it. Those tetrahedra are then exactly the periodic ones at the
// box's points (their stars are complete), and each periodic tetrahedron is taken once, by the
// copy whose least vertex lies in the box.
//
// A shell of width m* = h + sqrt(h^2 + H^2) needs no certificate, h being half the diagonal of a
// period and H the diagonal of the points' extent along the axes that are not periodic: the
// circumcentre c of a tetrahedron at point p lies in p's cell, within h of p along the periodic
// axes (p's own images bound it), and its sphere meets the points' extent within
// sqrt(h^2 + H^2) of c there, or it would hold an image of every point, a whole period, inside.
#ifndef fd3_PeriodicDelaunay_h
#define fd3_PeriodicDelaunay_h

#include "exact/PeriodicImages.h"
#include "fd3/Distributed.h"
#include "fd3/Periodic.h"
#include "fd3/Voronoi.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace fd3
{

class PeriodicDelaunay
{
public:
  /// Throws std::invalid_argument for a box with no periodic axis, or a periodic axis with
  /// hi <= lo or not finite.
  PeriodicDelaunay(
    const double* xyz, std::size_t count, const PeriodicBox& box, const Options& options);
  PeriodicTriangulation run();
  /// The cells of the box's points (voronoiCellsPeriodic()).
  VoronoiCells cells(const VoronoiOptions& options);

private:
  /// A point of the covering: the image of input point `owner` (a vertex of the box), moved by
  /// `offset` periods from the owner's place in the box.
  struct CoveringPoint
  {
    std::uint32_t owner;
    std::array<std::int8_t, 3> offset;
  };

  /// Wraps every finite point into the box (wraps, and each one's exact place), each a point of
  /// the box until its images show it repeats another; false where one lies too far.
  bool wrapPoints();
  /// The frame of the covering at its widest: the box and the widest shell, or the points'
  /// extent along the axes that are not periodic.
  void chooseFrame();
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
  /// The shell width that the mesh's tetrahedra at points of the box need, from their spheres:
  /// `margin_` where the certificate holds.
  double neededMargin(const IncrementalDelaunay& mesh) const;
  /// Whether the hull face (a, b, c) of covering points is parallel to every periodic axis,
  /// exactly.
  bool parallelToPeriods(const std::uint32_t face[3]) const;
  void extract(const Triangulation& covering, PeriodicTriangulation& out) const;

  const double* xyz_;
  std::size_t count_;
  PeriodicBox box_;
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
  std::vector<std::uint32_t> points_; // the box's points: the representatives of themselves
  std::size_t duplicates_ = 0, close_ = 0, nonFinite_ = 0;
  // The covering, batch after batch: its records (input units), images, and what each point is.
  std::vector<double> coveringXyz_;
  std::vector<ImageOf> coveringImages_;
  std::vector<CoveringPoint> covering_;
  std::vector<std::uint8_t> inBox_; // whether each covering point is a point of the box
};

} // namespace fd3

#endif
