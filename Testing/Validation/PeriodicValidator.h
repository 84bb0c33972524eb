// Independent exact check of a periodic tetrahedralization (GMP rationals, no code shared with
// Core): the oracle of the periodic tests. The periodic point set repeats the points along the
// periodic axes of a box; a periodic tetrahedron names four points and, for each, the image used.
#ifndef fd3_PeriodicValidator_h
#define fd3_PeriodicValidator_h

#include "ExactValidator.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fd3test
{

/// The box [lo, hi) on each axis, repeated along the axes where `periodic` is set, with period
/// hi - lo.
struct PeriodicDomain
{
  double lo[3] = {0, 0, 0};
  double hi[3] = {1, 1, 1};
  bool periodic[3] = {true, true, true};
};

/// Four point ids and the image of each: point ids[i], wrapped into the box along the periodic
/// axes (exactly, by a whole number of periods), moved by offsets[i] periods.
struct PeriodicTetrahedron
{
  std::array<std::uint32_t, 4> ids;
  std::array<std::array<std::int32_t, 3>, 4> offsets;
};

/// Checks that `tets`, each taken with all its translates by whole periods, is a Delaunay
/// tetrahedralization of the periodic point set, each periodic tetrahedron listed once:
/// - ids in range, offsets 0 on the axes that are not periodic, every tetrahedron positive;
/// - no periodic tetrahedron listed twice (nor two translates of one);
/// - every face shared, up to a translation, by two tetrahedra with opposite orientations, or
///   (where an axis is not periodic) a hull face: its normal along the axes that are not periodic
///   only, with every point on its inner side;
/// - the volumes sum to one period of the hull: the box's volume where every axis is periodic;
/// - every distinct finite point (points that wrap to the same position are one) a vertex, by one
///   id; points that are not finite are no vertices;
/// - with `requireDelaunay`, every interior face locally Delaunay: the fourth point of either
///   tetrahedron, carried into the other's frame, not strictly inside its circumsphere.
/// Positive orientation, paired faces and the volume make the translates a triangulation of the
/// hull of the periodic set; local Delaunay faces then make it Delaunay.
ValidityReport checkPeriodicTriangulation(const double* xyz, std::size_t count,
  const PeriodicDomain& domain, const std::vector<PeriodicTetrahedron>& tets,
  bool requireDelaunay = true);
/// The same for weighted points (options.weights, every image with its point's weight): a regular
/// tetrahedralization of the periodic set. Interior faces must be locally regular, and each point
/// of options.hidden hidden: no vertex, and of non-negative power distance to the orthogonal
/// sphere of a tetrahedron (some translate) that contains it, or lighter than another point at
/// its position. Every other distinct point must be a vertex, except copies of a hidden point,
/// and the hull and its volume are the vertices'.
ValidityReport checkPeriodicTriangulation(const double* xyz, std::size_t count,
  const PeriodicDomain& domain, const std::vector<PeriodicTetrahedron>& tets,
  const ValidityOptions& options);

} // namespace fd3test

#endif
