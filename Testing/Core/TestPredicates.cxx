// The kernel's predicates against exact rational arithmetic on random and adversarial inputs.
#include "ExactValidator.h"
#include "exact/Predicates.h"

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace
{
using fd3test::exactInSphere;
using fd3test::exactOrient3d;

fd3::Bounds boxOf(const std::vector<double>& xyz)
{
  return fd3::finiteBounds(xyz.data(), xyz.size() / 3);
}

// Squared distance from e to the circumcentre, minus the squared circumradius, in rationals:
// a definition of "inside" independent of any determinant formula.
int insideByCircumcentre(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  mpq_class m[3][3], rhs[3];
  const double* q[3] = {b, c, d};
  for (int i = 0; i < 3; ++i)
  {
    rhs[i] = 0;
    for (int k = 0; k < 3; ++k)
    {
      m[i][k] = 2 * (mpq_class(q[i][k]) - mpq_class(a[k]));
      rhs[i] += mpq_class(q[i][k]) * q[i][k] - mpq_class(a[k]) * a[k];
    }
  }
  // Cramer's rule for the circumcentre.
  auto det = [](mpq_class r0[3], mpq_class r1[3], mpq_class r2[3]) -> mpq_class {
    return r0[0] * (r1[1] * r2[2] - r1[2] * r2[1]) - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0]) +
      r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]);
  };
  const mpq_class D = det(m[0], m[1], m[2]);
  mpq_class centre[3];
  for (int k = 0; k < 3; ++k)
  {
    mpq_class c0[3], c1[3], c2[3];
    for (int j = 0; j < 3; ++j)
    {
      c0[j] = j == k ? rhs[0] : m[0][j];
      c1[j] = j == k ? rhs[1] : m[1][j];
      c2[j] = j == k ? rhs[2] : m[2][j];
    }
    centre[k] = det(c0, c1, c2) / D;
  }
  mpq_class r2 = 0, d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    r2 += (centre[k] - a[k]) * (centre[k] - a[k]);
    d2 += (centre[k] - e[k]) * (centre[k] - e[k]);
  }
  return sgn(r2 - d2);
}

// The filter's error bounds hold for one order of operations; the SSE2 form must give the plain
// form's double bit for bit, on spread and on nearly cospherical points, at every scale.
TEST(Predicates, InSphereDeterminantLanesGiveThePlainDouble)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t compared = 0;
  for (double scale : {1.0, 1e-3, 1e-9, 3e5})
    for (int trial = 0; trial < 20000; ++trial)
    {
      double p[5][3];
      for (auto& q : p)
        for (double& x : q)
          x = scale * unit(rng);
      if (trial % 2 == 1) // e on the circumsphere of a regular-ish tetrahedron, up to rounding
      {
        const double r = scale * 0.5;
        for (int i = 0; i < 5; ++i)
        {
          const double z = unit(rng), phi = 3.14159 * unit(rng), s = std::sqrt(1 - z * z);
          p[i][0] = r * s * std::cos(phi);
          p[i][1] = r * s * std::sin(phi);
          p[i][2] = r * z;
        }
      }
      const double plain = fd3::inSphereDeterminantPlain(p[0], p[1], p[2], p[3], p[4]);
      const double lanes = fd3::inSphereDeterminant(p[0], p[1], p[2], p[3], p[4]);
      ASSERT_EQ(std::memcmp(&plain, &lanes, sizeof plain), 0)
        << "scale " << scale << ", trial " << trial << ": " << plain << " against " << lanes;
      ++compared;
    }
  EXPECT_EQ(compared, 80000u);
}

TEST(Predicates, SignConventionsOnTheUnitTetrahedron)
{
  fd3::Predicates predicates;
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0, 0, 1};
  const double inside[3] = {0.25, 0.25, 0.25}, outside[3] = {2, 2, 2}, onSphere[3] = {1, 1, 1};
  EXPECT_EQ(predicates.orient3d(a, b, c, d), 1);
  EXPECT_EQ(predicates.orient3d(b, a, c, d), -1);
  EXPECT_EQ(predicates.orient3d(a, b, c, inside), 1);
  EXPECT_EQ(predicates.orient3d(a, b, c, b), 0);
  EXPECT_EQ(predicates.inSphere(a, b, c, d, inside), 1);
  EXPECT_EQ(predicates.inSphere(a, b, c, d, outside), -1);
  EXPECT_EQ(predicates.inSphere(a, b, c, d, onSphere), 0);
  EXPECT_EQ(exactInSphere(a, b, c, d, inside), 1);
  EXPECT_EQ(exactInSphere(a, b, c, d, onSphere), 0);
  EXPECT_EQ(insideByCircumcentre(a, b, c, d, inside), 1);
}

// Points near a plane or a sphere, perturbed by a few ulps: the float filter fails and the exact
// path decides. Compared with GMP on every call.
class PredicatesAgainstRationals : public ::testing::TestWithParam<double>
{};

TEST_P(PredicatesAgainstRationals, AgreeOnNearDegenerateInput)
{
  const double scale = GetParam();
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::uniform_int_distribution<int> ulps(-3, 3);
  fd3::Predicates predicates;
  auto nudge = [&](double x) {
    for (int i = ulps(rng); i != 0; i += (i < 0 ? 1 : -1))
      x = std::nextafter(x, i < 0 ? -INFINITY : INFINITY);
    return x;
  };
  int ties = 0, decided = 0;
  for (int trial = 0; trial < 3000; ++trial)
  {
    double p[5][3];
    for (auto& q : p)
      for (double& x : q)
        x = uniform(rng) * scale;
    // d on the plane abc, then nudged.
    const double s = uniform(rng), t = uniform(rng);
    for (int k = 0; k < 3; ++k)
      p[3][k] = nudge(p[0][k] + s * (p[1][k] - p[0][k]) + t * (p[2][k] - p[0][k]));
    const int o = predicates.orient3d(p[0], p[1], p[2], p[3]);
    ASSERT_EQ(o, exactOrient3d(p[0], p[1], p[2], p[3]));
    ties += o == 0;
    // e on the sphere through the 4 points of a well-shaped tetrahedron, then nudged: a point on
    // a sphere is built as centre + radius * unit direction, which is close but rarely exact.
    double q[4][3] = {{-scale, -scale, -scale}, {scale, -scale, scale}, {-scale, scale, scale},
      {scale, scale, -scale}}; // regular tetrahedron, circumcentre 0, radius sqrt(3)*scale
    double dir[3] = {uniform(rng), uniform(rng), uniform(rng)};
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double e[3];
    for (int k = 0; k < 3; ++k)
      e[k] = nudge(dir[k] / len * std::sqrt(3.0) * scale);
    if (predicates.orient3d(q[0], q[1], q[2], q[3]) < 0)
      std::swap(q[0], q[1]);
    const int s1 = predicates.inSphere(q[0], q[1], q[2], q[3], e);
    ASSERT_EQ(s1, exactInSphere(q[0], q[1], q[2], q[3], e));
    ASSERT_EQ(s1, insideByCircumcentre(q[0], q[1], q[2], q[3], e));
    // Random tetrahedra and points, mostly decided by the filter.
    if (exactOrient3d(p[0], p[1], p[2], p[4]) > 0)
    {
      ASSERT_EQ(predicates.inSphere(p[0], p[1], p[2], p[4], p[3]),
        exactInSphere(p[0], p[1], p[2], p[4], p[3]));
      ++decided;
    }
  }
  EXPECT_GT(predicates.exactOrientCalls + predicates.exactInSphereCalls, 100u)
    << "the adversarial inputs should defeat the float filter";
  EXPECT_GT(decided, 100);
  (void)ties;
}

// The predicates' contract is coordinates within [-1, 1] (Core normalizes exactly before calling);
// small scales exercise the underflow guard of the filter.
INSTANTIATE_TEST_SUITE_P(Scales, PredicatesAgainstRationals, ::testing::Values(1.0, 1e-5, 1e-40));

// Predicates adapted to a point set (static filter bounds, integer-grid exact stages, and float
// evaluations that are exact on small grids) against GMP, at grid sizes on both sides of each
// threshold. Coordinates are drawn from the extremes of the grid (the worst case for the bounds)
// and from a coarse sub-lattice (cospherical and coplanar ties), as well as at random.
class AdaptedPredicates : public ::testing::TestWithParam<int>
{};

TEST_P(AdaptedPredicates, AgreeWithRationalsOnGridPoints)
{
  const int bits = GetParam(); // coordinates: integers below 2^bits, in units of 2^-bits
  const double unit = std::ldexp(1.0, -bits);
  const std::int64_t largest = (std::int64_t(1) << bits) - 1;
  std::mt19937_64 rng(bits);
  std::uniform_int_distribution<std::int64_t> any(-largest, largest), coarse(-2, 2), pick(0, 3);
  auto coordinate = [&]() -> double {
    switch (pick(rng))
    {
      case 0:
        return double(largest) * unit;
      case 1:
        return -double(largest) * unit;
      case 2:
        return double(coarse(rng) * (largest / 2)) * unit;
      default:
        return double(any(rng)) * unit;
    }
  };
  std::vector<double> xyz(3 * 2000);
  for (double& x : xyz)
    x = coordinate();
  xyz[0] = -double(largest) * unit; // the grid's extent and unit are fixed by the set
  xyz[1] = unit;
  // Grid points exactly on the sphere of radius R = m^2 + n^2 + p^2 + q^2 (as large as the grid
  // allows), from Euler's four-square identity: the largest coordinates, and all ties. Each
  // comes with a neighbour one unit off, a near tie.
  const std::int64_t radius = std::min<std::int64_t>(largest, (std::int64_t(1) << 26) - 1);
  const auto root = static_cast<std::int64_t>(std::sqrt(double(radius)));
  std::uniform_int_distribution<std::int64_t> part(0, root);
  for (int found = 0, tries = 0; found < 60 && tries < 1000000; ++tries)
  {
    const std::int64_t m = part(rng), n = part(rng), p = part(rng);
    const std::int64_t rest = radius - m * m - n * n - p * p;
    const auto q =
      static_cast<std::int64_t>(std::llround(std::sqrt(double(std::max<std::int64_t>(rest, 0)))));
    if (rest < 0 || q * q != rest)
      continue;
    const double c[3] = {double(m * m + n * n - p * p - q * q), double(2 * (m * q + n * p)),
      double(2 * (n * q - m * p))};
    for (int k = 0; k < 3; ++k)
      xyz.push_back(c[k] * unit);
    for (int k = 0; k < 3; ++k)
      xyz.push_back((c[k] + (k == 0 ? (c[0] > 0 ? -1 : 1) : 0)) * unit);
    ++found;
  }
  const std::size_t sphereFirst = 2000, sphereCount = xyz.size() / 3 - sphereFirst;
  ASSERT_GE(sphereCount, 40u);
  fd3::Predicates predicates;
  predicates.adaptTo(xyz.data(), xyz.size() / 3, 3, boxOf(xyz));
  std::uniform_int_distribution<std::size_t> point(0, sphereFirst - 1),
    onSphere(0, sphereCount - 1);
  int orientTies = 0, sphereTies = 0;
  for (int trial = 0; trial < 20000; ++trial)
  {
    const double* p[5];
    for (auto& q : p)
      q = xyz.data() + 3 * (trial % 2 ? point(rng) : sphereFirst + onSphere(rng));
    const int o = predicates.orient3d(p[0], p[1], p[2], p[3]);
    ASSERT_EQ(o, exactOrient3d(p[0], p[1], p[2], p[3]));
    orientTies += o == 0;
    if (o > 0)
    {
      const int s = predicates.inSphere(p[0], p[1], p[2], p[3], p[4]);
      ASSERT_EQ(s, exactInSphere(p[0], p[1], p[2], p[3], p[4]));
      sphereTies += s == 0;
    }
  }
  EXPECT_GT(orientTies, 100);
  EXPECT_GT(sphereTies, 10);
}

INSTANTIATE_TEST_SUITE_P(
  GridBits, AdaptedPredicates, ::testing::Values(3, 8, 9, 15, 16, 23, 24, 40));

// Off any grid, an adapted set decides well-spread points with its static bounds and the rest
// with the semi-static filter and expansions; agreement with GMP on nearly degenerate input.
TEST(Predicates, AdaptedStaticFilterAgreesWithRationals)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::vector<double> xyz(3 * 1000);
  for (double& x : xyz)
    x = uniform(rng);
  fd3::Predicates predicates;
  predicates.adaptTo(xyz.data(), xyz.size() / 3, 3, boxOf(xyz));
  for (int trial = 0; trial < 20000; ++trial)
  {
    const double* a = &xyz[3 * (trial % 1000)];
    const double* b = &xyz[3 * ((trial * 7 + 1) % 1000)];
    const double* c = &xyz[3 * ((trial * 13 + 2) % 1000)];
    // d and e close to the plane abc, or tiny tetrahedra: both stages get exercised.
    const double s = uniform(rng), t = uniform(rng), lift = std::ldexp(uniform(rng), -(trial % 60));
    double d[3], e[3];
    for (int k = 0; k < 3; ++k)
    {
      d[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]) + lift;
      e[k] = a[k] + lift * uniform(rng);
    }
    ASSERT_EQ(predicates.orient3d(a, b, c, d), exactOrient3d(a, b, c, d));
    if (exactOrient3d(a, b, c, d) > 0)
      ASSERT_EQ(predicates.inSphere(a, b, c, d, e), exactInSphere(a, b, c, d, e));
  }
  EXPECT_GT(predicates.exactOrientCalls, 0u);
}

// Surface samples leave most insphere tests to the lifts' filter: tetrahedra far smaller than
// the box (the static bound is the box's), nearly cospherical with the fifth point, some with one
// vertex far off (a thin tetrahedron across the surface). Every sign the float stage gives must be
// the exact one, and it must give most of them: 92% (the semi-static bound alone, 79%). With the
// lifts' filter first (preferLiftsFilter(), what the kernel switches to on surface samples), every
// verdict is the same, undecided ones included.
TEST(Predicates, LiftFilterGivesExactSignsOnSmallAndThinTetrahedra)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Spread points off any grid (the tuning then relies on no grid) spanning the box.
  std::vector<double> spread = {-1, -1, -1, 1, 1, 1};
  for (int i = 0; i < 3000; ++i)
    spread.push_back(unit(rng));
  fd3::Predicates predicates;
  predicates.adaptTo(spread.data(), spread.size() / 3, 3, boxOf(spread));
  fd3::Predicates liftsFirst;
  liftsFirst.tuneLike(predicates);
  liftsFirst.preferLiftsFilter();
  std::size_t decided = 0, trials = 0;
  for (double scale : {1e-2, 1e-4, 1e-7})
    for (double nearness : {1e-3, 1e-7, 1e-11, 1e-15})
      for (int trial = 0; trial < 2000; ++trial, ++trials)
      {
        double centre[3], p[5][3];
        for (double& x : centre)
          x = 0.5 * unit(rng);
        for (int i = 0; i < 5; ++i)
        {
          const double z = unit(rng), phi = 3.14159265 * unit(rng), s = std::sqrt(1 - z * z);
          const double r = scale * (i == 4 ? 1 + nearness * unit(rng) : 1.0);
          const double far = i == 3 && trial % 3 == 0 ? 0.4 / scale : 1.0;
          const double direction[3] = {s * std::cos(phi), s * std::sin(phi), z};
          for (int k = 0; k < 3; ++k)
            p[i][k] = centre[k] + far * r * direction[k];
        }
        if (exactOrient3d(p[0], p[1], p[2], p[3]) < 0)
          std::swap(p[0], p[1]);
        const int sign = predicates.inSphereFiltered(p[0], p[1], p[2], p[3], p[4]);
        ASSERT_EQ(sign, liftsFirst.inSphereFiltered(p[0], p[1], p[2], p[3], p[4]))
          << "scale " << scale << ", nearness " << nearness << ", trial " << trial;
        if (sign == 0)
          continue;
        ++decided;
        ASSERT_EQ(sign, exactInSphere(p[0], p[1], p[2], p[3], p[4]))
          << "scale " << scale << ", nearness " << nearness << ", trial " << trial;
      }
  EXPECT_GT(decided, trials * 85 / 100);
  // The default order counts what the lifts' filter decided after the static one could not:
  // the figure by which the kernel switches.
  EXPECT_GT(predicates.liftsFilterRescues(), decided / 2);
  EXPECT_EQ(liftsFirst.liftsFilterRescues(), 0u);
}

// Near-degenerate inspheres off any grid, as thin tetrahedra on surface samples make them: five
// points rounded onto one sphere, and four points near one circle (a sliver) with any fifth. The
// float filters cannot decide them, double-double decides almost all, and every verdict is exact.
TEST(Predicates, DoubleDoubleStageDecidesNearDegenerateInSpheres)
{
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-1, 1);
  auto onSphere = [&](double radius, const double centre[3], double* out) {
    double r = 0;
    for (int k = 0; k < 3; ++k)
    {
      out[k] = normal(rng);
      r += out[k] * out[k];
    }
    for (int k = 0; k < 3; ++k)
      out[k] = centre[k] + radius * out[k] / std::sqrt(r);
  };
  fd3::Predicates predicates;
  int decided = 0;
  for (int trial = 0; trial < 4000; ++trial)
  {
    double p[5][3];
    const double centre[3] = {0.3 * uniform(rng), 0.3 * uniform(rng), 0.3 * uniform(rng)};
    const double radius = std::ldexp(0.5, -(trial % 20));
    for (auto& q : p)
      onSphere(radius, centre, q);
    if (trial % 2)
    {
      // A sliver: the four points of the tetrahedron near one circle of the sphere (z = centre).
      for (int i = 0; i < 4; ++i)
        p[i][2] = centre[2] + radius * 1e-9 * uniform(rng);
    }
    if (exactOrient3d(p[0], p[1], p[2], p[3]) < 0)
      std::swap(p[0], p[1]);
    if (exactOrient3d(p[0], p[1], p[2], p[3]) == 0)
      continue;
    const std::size_t before = predicates.doubleDoubleInSphereCalls;
    ASSERT_EQ(predicates.inSphere(p[0], p[1], p[2], p[3], p[4]),
      exactInSphere(p[0], p[1], p[2], p[3], p[4]))
      << "trial " << trial;
    decided += predicates.doubleDoubleInSphereCalls > before;
  }
  EXPECT_GT(decided, 1000) << "the float filters should leave these open";
  EXPECT_LT(predicates.exactInSphereCalls * 20, predicates.doubleDoubleInSphereCalls)
    << predicates.exactInSphereCalls << " of " << predicates.doubleDoubleInSphereCalls
    << " went on to the exact stage";
}

// Four of the five points in a plane perpendicular to an axis (a face of a structured grid, a
// layer, a ring): the sign then comes from the fifth point's side and an incircle test in the
// plane. It must be the rationals' for every axis and every position of the point off the plane, on
// exact ties (rectangles, and rings whose points swap coordinates), near ties (a rectangle one ulp
// off) and clear cases.
TEST(Predicates, AxisPlaneInSpheresAgreeWithRationals)
{
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> uniform(-0.9, 0.9);
  fd3::Predicates predicates;
  int ties = 0, checked = 0;
  for (int trial = 0; trial < 6000; ++trial)
  {
    const int axis = trial % 3, off = trial / 3 % 5, variant = trial / 15 % 4;
    const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    double plane[4][2];
    const double x0 = uniform(rng), y0 = uniform(rng), h = 0.01 * (1 + uniform(rng));
    if (variant < 2) // a rectangle, exact or with one corner one ulp off
    {
      const double x1 = x0 + h / 3, y1 = y0 + h / 7;
      const double corners[4][2] = {{x0, y0}, {x1, y0}, {x0, y1}, {x1, y1}};
      std::memcpy(plane, corners, sizeof plane);
      if (variant == 1)
        plane[3][0] = std::nextafter(plane[3][0], 2.0);
    }
    else if (variant == 2) // a ring: (a, b), (-a, b), (a, -b), (b, a) have one norm exactly
    {
      const double t = uniform(rng), a = 0.5 * std::cos(t), b = 0.5 * std::sin(t);
      const double ring[4][2] = {{a, b}, {-a, b}, {a, -b}, {b, a}};
      std::memcpy(plane, ring, sizeof plane);
    }
    else
      for (auto& q : plane)
        q[0] = uniform(rng), q[1] = uniform(rng);
    double p[5][3];
    const double level = uniform(rng);
    for (int i = 0, j = 0; i < 5; ++i)
    {
      if (i == off)
      {
        p[i][0] = uniform(rng), p[i][1] = uniform(rng), p[i][2] = uniform(rng);
        continue;
      }
      p[i][axis] = level;
      p[i][u] = plane[j][0];
      p[i][v] = plane[j++][1];
    }
    if (exactOrient3d(p[0], p[1], p[2], p[3]) < 0)
      std::swap(p[0], p[1]);
    if (exactOrient3d(p[0], p[1], p[2], p[3]) == 0)
      continue;
    const int expected = exactInSphere(p[0], p[1], p[2], p[3], p[4]);
    ASSERT_EQ(predicates.inSphere(p[0], p[1], p[2], p[3], p[4]), expected)
      << "trial " << trial << ", axis " << axis << ", off " << off << ", variant " << variant;
    ties += expected == 0;
    ++checked;
  }
  EXPECT_GT(checked, 4000);
  EXPECT_GT(ties, 500);
  // And the four in the plane are coplanar, without the exact stage's expansions.
  const double q[4][3] = {{0.1, 0.3, 0.7}, {0.2, 0.4, 0.7}, {-0.5, 0.3, 0.7}, {0.9, -0.1, 0.7}};
  EXPECT_EQ(predicates.orient3d(q[0], q[1], q[2], q[3]), 0);
}

// Four of the five points the corners of a rectangle with two sides along an axis, in a plane of
// any direction (an extruded profile's cells): a tie, settled without arithmetic, and a coplanar
// four. A corner one ulp off, or one edge moved along the axis, is no tie, and the exact stage
// decides it.
TEST(Predicates, AxisRectangleTiesAgreeWithRationals)
{
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> uniform(-0.9, 0.9);
  fd3::Predicates predicates;
  int ties = 0, checked = 0;
  for (int trial = 0; trial < 3000; ++trial)
  {
    const int axis = trial % 3, off = trial / 3 % 5;
    const bool nudged = trial / 15 % 2, staggered = trial / 30 % 3 == 0;
    double corner[2][3], p[5][3];
    for (auto& c : corner)
      for (double& x : c)
        x = uniform(rng);
    const double low = uniform(rng), high = low + 0.01 * (1.5 + uniform(rng));
    for (int i = 0, j = 0; i < 5; ++i)
    {
      if (i == off)
      {
        p[i][0] = uniform(rng), p[i][1] = uniform(rng), p[i][2] = uniform(rng);
        continue;
      }
      std::copy_n(corner[j % 2], 3, p[i]);
      // Staggered: the second edge moved along the axis, a trapezoid (coplanar, no tie).
      p[i][axis] = (j < 2 ? low : high) + (staggered && j % 2 ? 0.003 : 0.0);
      ++j;
    }
    if (nudged)
      p[off == 4 ? 3 : 4][(axis + 1) % 3] =
        std::nextafter(p[off == 4 ? 3 : 4][(axis + 1) % 3], 2.0);
    const int o = exactOrient3d(p[0], p[1], p[2], p[3]);
    if (o < 0)
      std::swap(p[0], p[1]);
    if (o == 0)
    {
      EXPECT_EQ(predicates.orient3d(p[0], p[1], p[2], p[3]), 0);
      continue;
    }
    const int expected = exactInSphere(p[0], p[1], p[2], p[3], p[4]);
    ASSERT_EQ(predicates.inSphere(p[0], p[1], p[2], p[3], p[4]), expected)
      << "trial " << trial << ", axis " << axis << ", off " << off << ", nudged " << nudged;
    ties += expected == 0;
    ++checked;
  }
  EXPECT_GT(checked, 2000);
  EXPECT_GT(ties, 500);
}

TEST(Predicates, ExactTiesOnIntegerLattice)
{
  fd3::Predicates predicates;
  // All 8 corners of a cube are cospherical; any 4 non-coplanar ones with a 5th give a tie.
  const double c[8][3] = {
    {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  EXPECT_EQ(predicates.inSphere(c[0], c[1], c[2], c[4], c[7]), 0);
  EXPECT_EQ(predicates.orient3d(c[0], c[1], c[2], c[3]), 0);
  EXPECT_TRUE(predicates.collinear(c[0], c[7], c[7]));
  const double mid[3] = {0.5, 0.5, 0.5};
  EXPECT_TRUE(predicates.collinear(c[0], c[7], mid));
  EXPECT_FALSE(predicates.collinear(c[0], c[7], c[1]));
}

TEST(Predicates, SymbolicPerturbationNeverTiesAndAgreesAcrossAFace)
{
  // The perturbation's order comes from the points' coordinates (and the seed). For cospherical
  // points the verdicts are never 0, and the two tetrahedra on either side of a face agree on it:
  // each has the other's far vertex in its sphere, or neither has.
  for (std::uint64_t seed = 1; seed <= 8; ++seed)
  {
    fd3::Predicates predicates(seed);
    const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
    std::uint32_t tets[][4] = {{0, 1, 2, 4}, {1, 3, 2, 7}, {1, 2, 4, 7}};
    for (auto& t : tets)
    {
      if (predicates.orient3d(xyz + 3 * t[0], xyz + 3 * t[1], xyz + 3 * t[2], xyz + 3 * t[3]) < 0)
        std::swap(t[0], t[1]);
      for (std::uint32_t e = 0; e < 8; ++e)
        if (e != t[0] && e != t[1] && e != t[2] && e != t[3])
        {
          const double* p[4] = {xyz + 3 * t[0], xyz + 3 * t[1], xyz + 3 * t[2], xyz + 3 * t[3]};
          EXPECT_NE(predicates.inSphereSoS(p, xyz + 3 * e), 0);
        }
    }
    // tets[0] and tets[2] share the face {1, 2, 4}; their far vertices are 0 and 7.
    auto points = [&xyz](const std::uint32_t* t, const double* out[4]) {
      for (int i = 0; i < 4; ++i)
        out[i] = xyz + 3 * t[i];
    };
    const double* first[4];
    const double* second[4];
    points(tets[0], first);
    points(tets[2], second);
    EXPECT_EQ(
      predicates.inSphereSoS(first, xyz + 3 * 7), predicates.inSphereSoS(second, xyz + 3 * 0))
      << "seed " << seed;
    EXPECT_GT(predicates.symbolicTies, 0u);
  }
}

} // namespace
