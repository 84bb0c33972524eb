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
/// With `lowered`, the orthocentre of weighted vertices instead (the power diagram's vertex): the
/// weights' differences w_u - w_0, w_v - w_0, w_w - w_0 lower the squared lengths.
inline Circumcentre circumcentreOfEdges(
  const double* u, const double* v, const double* w, const double* lowered = nullptr)
{
  // (|u|^2 (v x w) + |v|^2 (w x u) + |w|^2 (u x v)) / (2 u.(v x w)).
  const double vw[3] = {
    v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2], v[0] * w[1] - v[1] * w[0]};
  const double wu[3] = {
    w[1] * u[2] - w[2] * u[1], w[2] * u[0] - w[0] * u[2], w[0] * u[1] - w[1] * u[0]};
  const double uv[3] = {
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
  Circumcentre centre;
  centre.sixVolume = u[0] * vw[0] + u[1] * vw[1] + u[2] * vw[2];
  centre.edgeProduct2 = uu * vv * ww;
  if (lowered)
  {
    uu -= lowered[0];
    vv -= lowered[1];
    ww -= lowered[2];
  }
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

// Weighted points (power distance |x - p|^2 - w): the squared radius of the smallest sphere
// orthogonal to every weighted vertex of a simplex, the weighted alpha shape's measure. It is the
// circumradius squared where the weights are 0, and negative where the balls overlap enough. Each
// centre, relative to the first vertex, solves 2 d.c = |d|^2 - (w_d - w_0) for every edge d from
// it, in the simplex's affine hull: the circumcentre's formula with the weights in the lifts.

/// Of tetrahedron p (infinite when flat).
inline double tetrahedronOrthoradius2(const double* const p[4], const double w[4])
{
  double d[3][3], lift[3];
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
      d[i][k] = p[i + 1][k] - p[0][k];
    lift[i] = d[i][0] * d[i][0] + d[i][1] * d[i][1] + d[i][2] * d[i][2] - (w[i + 1] - w[0]);
  }
  double cross[3][3]; // d1 x d2, d2 x d0, d0 x d1
  for (int i = 0; i < 3; ++i)
  {
    const double* u = d[(i + 1) % 3];
    const double* v = d[(i + 2) % 3];
    cross[i][0] = u[1] * v[2] - u[2] * v[1];
    cross[i][1] = u[2] * v[0] - u[0] * v[2];
    cross[i][2] = u[0] * v[1] - u[1] * v[0];
  }
  const double six = d[0][0] * cross[0][0] + d[0][1] * cross[0][1] + d[0][2] * cross[0][2];
  if (six == 0)
    return INFINITY;
  double r2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double c =
      (lift[0] * cross[0][k] + lift[1] * cross[1][k] + lift[2] * cross[2][k]) / (2 * six);
    r2 += c * c;
  }
  return r2 - w[0];
}

/// Of triangle p (infinite when degenerate).
inline double triangleOrthoradius2(const double* const p[3], const double w[3])
{
  const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
  const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
  const double n[3] = {
    u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  if (n2 == 0)
    return INFINITY;
  const double lu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - (w[1] - w[0]);
  const double lv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - (w[2] - w[0]);
  // (lu (v x n) + lv (n x u)) / (2 |n|^2): u.c = lu / 2, v.c = lv / 2, and c in the plane.
  const double vn[3] = {
    v[1] * n[2] - v[2] * n[1], v[2] * n[0] - v[0] * n[2], v[0] * n[1] - v[1] * n[0]};
  const double nu[3] = {
    n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
  double r2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double c = (lu * vn[k] + lv * nu[k]) / (2 * n2);
    r2 += c * c;
  }
  return r2 - w[0];
}

/// Of edge ab (infinite when a == b).
inline double edgeOrthoradius2(const double* a, const double* b, double wa, double wb)
{
  const double length2 = distance2(a, b);
  if (length2 == 0)
    return INFINITY;
  const double t = (length2 - (wb - wa)) / (2 * length2); // the centre is a + t (b - a)
  return t * t * length2 - wa;
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
