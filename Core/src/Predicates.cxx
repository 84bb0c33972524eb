#include "Predicates.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace fd3
{
namespace
{
constexpr double kEpsilon = DBL_EPSILON / 2; // unit roundoff 2^-53
// Error bounds of the float evaluations below: Shewchuk's (1997) relative bounds, for differences
// of inputs, times a bound on the permanent from the largest differences; 2% covers the rounding
// of that product of maxima.
constexpr double kOrientSemiStatic = 1.02 * 6 * (7.0 + 56.0 * kEpsilon) * kEpsilon;
constexpr double kInSphereSemiStatic = 1.02 * 72 * (16.0 + 224.0 * kEpsilon) * kEpsilon;
// Below this magnitude products may have underflowed and the relative bounds no longer hold.
constexpr double kUnderflowGuard = 1e-250;

int signOf(double x)
{
  return (x > 0) - (x < 0);
}

template <typename T>
int signOf(T x)
{
  return (x > 0) - (x < 0);
}

using Int128 = __int128;

Int128 det3(const std::int64_t u[3], const std::int64_t v[3], const std::int64_t w[3])
{
  const Int128 cx = Int128(v[1]) * w[2] - Int128(v[2]) * w[1];
  const Int128 cy = Int128(v[2]) * w[0] - Int128(v[0]) * w[2];
  const Int128 cz = Int128(v[0]) * w[1] - Int128(v[1]) * w[0];
  return u[0] * cx + u[1] * cy + u[2] * cz;
}
} // namespace

double Predicates::integerGridUnit(const double* xyz, std::size_t count)
{
  int lowest = 4096, highest = -4096;
  for (std::size_t i = 0; i < 3 * count; ++i)
  {
    if (xyz[i] == 0.0)
      continue;
    int exponent;
    const double mantissa = std::frexp(xyz[i], &exponent);
    // The lowest set bit of the 53-bit significand gives the finest grid this value needs.
    const auto significand = static_cast<std::uint64_t>(std::ldexp(std::fabs(mantissa), 53));
    lowest = std::min(lowest, exponent - 53 + __builtin_ctzll(significand));
    highest = std::max(highest, exponent);
    if (highest - lowest > kIntegerGridBits)
      return 0.0;
  }
  return lowest <= highest ? std::ldexp(1.0, lowest) : 0.0;
}

// On the grid, coordinates are integers below 2^21 in magnitude, so differences are exact doubles
// and integers below 2^22: 3x3 minors stay below 2^69, lifts below 2^46, the insphere determinant
// below 2^118, and orient3d below 2^69 -- all exact in __int128.
template <int N>
void Predicates::gridDifferences(const double* const x[N], const double* y, std::int64_t out[N][3]) const
{
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < 3; ++k)
      out[i][k] = static_cast<std::int64_t>((x[i][k] - y[k]) * inverseGridUnit_);
}

int Predicates::orient3d(const double* a, const double* b, const double* c, const double* d)
{
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  // det[a-d; b-d; c-d] is the negative of VTK's orientation.
  const double det = adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) +
    cdz * (adx * bdy - bdx * ady);
  // Semi-static filter: the permanent is at most 6 * mx * my * mz, mx being the largest |x|
  // difference (and so on), so Shewchuk's bound (7 + 56 eps) eps * permanent is below
  // kOrientSemiStatic * mx * my * mz.
  const double mx = std::max({std::fabs(adx), std::fabs(bdx), std::fabs(cdx)});
  const double my = std::max({std::fabs(ady), std::fabs(bdy), std::fabs(cdy)});
  const double mz = std::max({std::fabs(adz), std::fabs(bdz), std::fabs(cdz)});
  const double scale = mx * my * mz;
  const double bound = kOrientSemiStatic * scale;
  if ((det > bound || -det > bound) && scale > kUnderflowGuard)
    return -signOf(det);
  return orient3dExact(a, b, c, d);
}

void Predicates::checkUnderflow(const double* const rows[], int count, const double* origin)
{
  for (int r = 0; r < count; ++r)
    for (int k = 0; k < 3; ++k)
    {
      const double d = std::fabs(rows[r][k] - origin[k]);
      if (d != 0.0 && d < kSmallestSafeDifference)
      {
        ++underflowRisks;
        return;
      }
    }
}

Expansion Predicates::minor3(Expansion const u[3], Expansion const v[3], Expansion const w[3])
{
  ExpansionArena& x = arena_;
  // u . (v x w)
  const Expansion cx = x.subtract(x.multiply(v[1], w[2]), x.multiply(v[2], w[1]));
  const Expansion cy = x.subtract(x.multiply(v[2], w[0]), x.multiply(v[0], w[2]));
  const Expansion cz = x.subtract(x.multiply(v[0], w[1]), x.multiply(v[1], w[0]));
  return x.add(x.add(x.multiply(u[0], cx), x.multiply(u[1], cy)), x.multiply(u[2], cz));
}

int Predicates::orient3dExact(const double* a, const double* b, const double* c, const double* d)
{
  ++exactOrientCalls;
  if (inverseGridUnit_ > 0)
  {
    const double* rows[3] = {b, c, d};
    std::int64_t q[3][3];
    gridDifferences<3>(rows, a, q);
    return signOf(det3(q[0], q[1], q[2]));
  }
  const double* rows[3] = {b, c, d};
  checkUnderflow(rows, 3, a);
  arena_.reset();
  Expansion u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = arena_.fromDifference(b[k], a[k]);
    v[k] = arena_.fromDifference(c[k], a[k]);
    w[k] = arena_.fromDifference(d[k], a[k]);
  }
  return static_cast<int>(minor3(u, v, w).sign());
}

int Predicates::inSphere(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  const double aex = a[0] - e[0], aey = a[1] - e[1], aez = a[2] - e[2];
  const double bex = b[0] - e[0], bey = b[1] - e[1], bez = b[2] - e[2];
  const double cex = c[0] - e[0], cey = c[1] - e[1], cez = c[2] - e[2];
  const double dex = d[0] - e[0], dey = d[1] - e[1], dez = d[2] - e[2];

  const double ab = aex * bey - bex * aey, bc = bex * cey - cex * bey, cd = cex * dey - dex * cey;
  const double da = dex * aey - aex * dey, ac = aex * cey - cex * aey, bd = bex * dey - dex * bey;
  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;
  const double alift = aex * aex + aey * aey + aez * aez;
  const double blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez;
  const double dlift = dex * dex + dey * dey + dez * dez;
  // det[(x-e, |x-e|^2) for x = a,b,c,d]; positive means inside for the negative orientation,
  // i.e. outside for VTK's positive one.
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);

  // Semi-static filter: each lift is at most 3 m^2 (m the largest difference) and each 3x3
  // permanent at most 6 mx my mz, so the permanent is at most 72 m^2 mx my mz and Shewchuk's bound
  // (16 + 224 eps) eps * permanent is below kInSphereSemiStatic * m^2 * mx * my * mz.
  const double mx = std::max({std::fabs(aex), std::fabs(bex), std::fabs(cex), std::fabs(dex)});
  const double my = std::max({std::fabs(aey), std::fabs(bey), std::fabs(cey), std::fabs(dey)});
  const double mz = std::max({std::fabs(aez), std::fabs(bez), std::fabs(cez), std::fabs(dez)});
  const double m = std::max({mx, my, mz});
  const double scale = m * m * mx * my * mz;
  const double bound = kInSphereSemiStatic * scale;
  if ((det > bound || -det > bound) && scale > kUnderflowGuard)
    return -signOf(det);
  return inSphereExact(a, b, c, d, e);
}

int Predicates::inSphereExact(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  ++exactInSphereCalls;
  if (inverseGridUnit_ > 0)
  {
    const double* rows[4] = {a, b, c, d};
    std::int64_t q[4][3];
    gridDifferences<4>(rows, e, q);
    Int128 lift[4];
    for (int r = 0; r < 4; ++r)
      lift[r] = Int128(q[r][0]) * q[r][0] + Int128(q[r][1]) * q[r][1] + Int128(q[r][2]) * q[r][2];
    const Int128 det = lift[1] * det3(q[0], q[2], q[3]) - lift[0] * det3(q[1], q[2], q[3]) +
      lift[3] * det3(q[0], q[1], q[2]) - lift[2] * det3(q[0], q[1], q[3]);
    return -signOf(det);
  }
  ExpansionArena& x = arena_;
  x.reset();
  const double* rows[4] = {a, b, c, d};
  checkUnderflow(rows, 4, e);
  Expansion diff[4][3], lift[4];
  for (int r = 0; r < 4; ++r)
  {
    for (int k = 0; k < 3; ++k)
      diff[r][k] = x.fromDifference(rows[r][k], e[k]);
    lift[r] = x.add(x.add(x.multiply(diff[r][0], diff[r][0]), x.multiply(diff[r][1], diff[r][1])),
      x.multiply(diff[r][2], diff[r][2]));
  }
  // Laplace expansion along the lift column of det[(x-e, |x-e|^2)].
  const Expansion m0 = minor3(diff[1], diff[2], diff[3]);
  const Expansion m1 = minor3(diff[0], diff[2], diff[3]);
  const Expansion m2 = minor3(diff[0], diff[1], diff[3]);
  const Expansion m3 = minor3(diff[0], diff[1], diff[2]);
  const Expansion det = x.add(x.subtract(x.multiply(lift[1], m1), x.multiply(lift[0], m0)),
    x.subtract(x.multiply(lift[3], m3), x.multiply(lift[2], m2)));
  return -static_cast<int>(det.sign());
}

bool Predicates::collinear(const double* a, const double* b, const double* c)
{
  arena_.reset();
  Expansion u[3], v[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = arena_.fromDifference(b[k], a[k]);
    v[k] = arena_.fromDifference(c[k], a[k]);
  }
  for (int k = 0; k < 3; ++k)
  {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Expansion cross =
      arena_.subtract(arena_.multiply(u[i], v[j]), arena_.multiply(u[j], v[i]));
    if (cross.sign() != 0)
      return false;
  }
  return true;
}

int Predicates::inSphereSoS(const double* xyz, const std::uint32_t tet[4], std::uint32_t e)
{
  const double* p[4] = {xyz + 3 * std::size_t(tet[0]), xyz + 3 * std::size_t(tet[1]),
    xyz + 3 * std::size_t(tet[2]), xyz + 3 * std::size_t(tet[3])};
  const double* pe = xyz + 3 * std::size_t(e);
  const int s = inSphere(p[0], p[1], p[2], p[3], pe);
  if (s != 0)
    return s;
  ++symbolicTies;
  // Lowering the lift of point v by delta_v changes (plane - lift)(e) by
  //   delta_e - sum_{v in tet} delta_v * lambda_v(e),
  // lambda_v(e) being the barycentric coordinate of e, whose sign is orient3d(tet with v := e).
  // The term of the smallest id dominates; the first non-zero one decides.
  int order[4] = {0, 1, 2, 3};
  std::sort(order, order + 4, [&](int i, int j) { return tet[i] < tet[j]; });
  for (int k : order)
  {
    if (e < tet[k])
      return 1;
    const double* q[4] = {p[0], p[1], p[2], p[3]};
    q[k] = pe;
    const int o = orient3d(q[0], q[1], q[2], q[3]);
    if (o != 0)
      return -o;
  }
  return 1; // e has the largest id: its own lowering decides
}

} // namespace fd3
