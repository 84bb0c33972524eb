// Independent exact check of a tetrahedralization (GMP rationals, no code shared with Core):
// the oracle of every test. A double-precision evaluation with a very wide error margin settles
// clear cases; everything else is decided with exact rational arithmetic.
#ifndef fd3_ExactValidator_h
#define fd3_ExactValidator_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fd3test
{

struct ValidityReport
{
  std::vector<std::string> errors; // empty when valid
  std::size_t tetrahedra = 0;
  std::size_t hullFaces = 0;
  std::size_t interiorFaces = 0;
  std::size_t distinctPoints = 0;
  std::size_t usedVertices = 0;
  bool valid() const { return errors.empty(); }
  std::string summary() const;
};

struct ValidityOptions
{
  bool requireDelaunay = true; ///< every interior face locally Delaunay (or regular)
  /// Weighted points (a regular tetrahedralization): the weight of each point, its power distance
  /// to x being |x - p|^2 - w. Interior faces must then be locally regular, and each point of
  /// `hidden` hidden: no vertex, and of non-negative power distance to the orthogonal sphere of a
  /// tetrahedron that contains it (or lighter than the vertex at its position). Every other
  /// distinct finite point must be a vertex, except the copies of a hidden point.
  const double* weights = nullptr;
  std::vector<std::uint32_t> hidden;
};

/// Checks that `tets` (4 point ids each) is a triangulation of the convex hull of the distinct
/// finite points among `xyz`: positive orientation, conforming faces, boundary equal to the hull
/// (a closed, connected, locally convex surface covering every point once), every distinct point a
/// vertex exactly once, and (optionally) every interior face locally Delaunay.
ValidityReport checkTriangulation(const double* xyz, std::size_t count, const std::uint32_t* tets,
  std::size_t tetCount, const ValidityOptions& options = ValidityOptions());
/// The same, for any contiguous container of 4 ids per tetrahedron.
template <typename Ids>
ValidityReport checkTriangulation(const double* xyz, std::size_t count, const Ids& tets,
  const ValidityOptions& options = ValidityOptions())
{
  return checkTriangulation(xyz, count, tets.data(), tets.size() / 4, options);
}

/// The tetrahedra as a sorted list of sorted 4-tuples: equal for two triangulations exactly when
/// they have the same tetrahedra, whatever their order and orientation.
std::vector<std::array<std::uint32_t, 4>> canonicalTetrahedra(
  const std::uint32_t* tets, std::size_t tetCount);
template <typename Ids>
std::vector<std::array<std::uint32_t, 4>> canonicalTetrahedra(const Ids& tets)
{
  return canonicalTetrahedra(tets.data(), tets.size() / 4);
}

/// Sign of (b-a) x (c-a) . (d-a), exactly.
int exactOrient3d(const double* a, const double* b, const double* c, const double* d);
/// > 0 iff e is strictly inside the circumsphere of the positively oriented tetrahedron abcd.
int exactInSphere(
  const double* a, const double* b, const double* c, const double* d, const double* e);
/// > 0 iff e (weight we) has a negative power distance to the orthogonal sphere of the positively
/// oriented tetrahedron p[0..3] (weights w[0..3]), exactly.
int exactPowerTest(const double* const p[4], const double* e, const double w[4], double we);

} // namespace fd3test

#endif
