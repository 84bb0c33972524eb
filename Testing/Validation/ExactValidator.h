// Independent exact check of a tetrahedralization (GMP rationals, no code shared with Core):
// the oracle of every test. A double-precision evaluation with a very wide error margin settles
// clear cases; everything else is decided with exact rational arithmetic.
#ifndef fd3_ExactValidator_h
#define fd3_ExactValidator_h

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
  bool requireDelaunay = true; ///< every interior face locally Delaunay
};

/// Checks that `tets` (4 point ids each) is a triangulation of the convex hull of the distinct
/// finite points among `xyz`: positive orientation, conforming faces, boundary equal to the hull
/// (a closed, connected, locally convex surface covering every point once), every distinct point a
/// vertex exactly once, and (optionally) every interior face locally Delaunay.
ValidityReport checkTriangulation(const double* xyz, std::size_t count,
  const std::vector<std::uint32_t>& tets, const ValidityOptions& options = ValidityOptions());

/// Sign of (b-a) x (c-a) . (d-a), exactly.
int exactOrient3d(const double* a, const double* b, const double* c, const double* d);
/// > 0 iff e is strictly inside the circumsphere of the positively oriented tetrahedron abcd.
int exactInSphere(const double* a, const double* b, const double* c, const double* d, const double* e);

} // namespace fd3test

#endif
