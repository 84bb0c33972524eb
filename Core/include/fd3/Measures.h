// Floating-point measures of simplices, for thresholds and output arrays (not for decisions the
// triangulation's validity depends on: those go through the exact predicates).
#ifndef fd3_Measures_h
#define fd3_Measures_h

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace fd3
{

inline double distance2(const double* a, const double* b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

/// Six times the signed volume of tetrahedron abcd (positive for VTK's orientation).
inline double sixVolume(const double* a, const double* b, const double* c, const double* d)
{
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1] +
    (u[0] * v[1] - u[1] * v[0]) * w[2];
}

/// The circumcentre of tetrahedron abcd as an offset from a, with what tells how far it can be
/// trusted: six times the signed volume (0: flat, no centre; the offset is then 0) and
/// |ab|^2 |ac|^2 |ad|^2, whose root over |sixVolume| bounds the condition of the offset.
struct Circumcentre
{
  double offset[3] = {0, 0, 0};
  double sixVolume = 0;
  double edgeProduct2 = 0;
};

/// The circumcentre of the tetrahedron with vertices 0, u, v, w (edge vectors from one vertex).
inline Circumcentre circumcentreOfEdges(const double* u, const double* v, const double* w)
{
  // (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2 u.(v x w)).
  const double vw[3] = {
    v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2], v[0] * w[1] - v[1] * w[0]};
  const double wu[3] = {
    w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0]};
  const double uv[3] = {
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  const double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  Circumcentre centre;
  centre.sixVolume = u[0] * vw[0] + u[1] * vw[1] + u[2] * vw[2];
  centre.edgeProduct2 = uu * vv * ww;
  if (centre.sixVolume != 0)
  {
    const double inverse = 0.5 / centre.sixVolume; // one division, not three: the halo's pass
    for (int k = 0; k < 3; ++k)
      centre.offset[k] = (uu * vw[k] + vv * wu[k] + ww * uv[k]) * inverse;
  }
  return centre;
}

inline Circumcentre circumcentre(const double* a, const double* b, const double* c, const double* d)
{
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return circumcentreOfEdges(u, v, w);
}

/// Squared circumradius of tetrahedron abcd (infinite when flat).
inline double tetrahedronCircumradius2(
  const double* a, const double* b, const double* c, const double* d)
{
  const Circumcentre centre = circumcentre(a, b, c, d);
  if (centre.sixVolume == 0)
    return INFINITY;
  double r2 = 0;
  for (int k = 0; k < 3; ++k)
    r2 += centre.offset[k] * centre.offset[k];
  return r2;
}

/// Squared circumradius of triangle abc (infinite when degenerate).
inline double triangleCircumradius2(const double* a, const double* b, const double* c)
{
  const double ab = distance2(a, b), bc = distance2(b, c), ca = distance2(c, a);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double twiceArea2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2]; // (2 area)^2
  return twiceArea2 > 0 ? ab * bc * ca / (4 * twiceArea2) : INFINITY;
}

/// Circumradius over shortest edge: sqrt(3/8) ~ 0.612 for the regular tetrahedron, large for
/// slivers and needles.
inline double radiusEdgeRatio(const double* a, const double* b, const double* c, const double* d)
{
  const double shortest2 = std::min({distance2(a, b), distance2(a, c), distance2(a, d),
    distance2(b, c), distance2(b, d), distance2(c, d)});
  return std::sqrt(tetrahedronCircumradius2(a, b, c, d) / shortest2);
}

} // namespace fd3

#endif
