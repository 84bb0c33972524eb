// Degenerate, hostile and huge inputs: every result must pass the exact validator.
#include "CoreTestUtilities.h"
#include "ExactValidator.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

namespace
{
using fd3test::joined;
using fd3test::Points;
using fd3test::scaled;

fd3::Triangulation expectExactDelaunay(const Points& p, const std::string& what, int threads = 1)
{
  fd3::Options options;
  options.threads = threads;
  options.pointsPerThread = 64; // parallel rounds even on these small sets
  return fd3test::triangulateAndCheck(p, options, what);
}

Points subset(const Points& p, double keep, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution take(keep);
  Points out;
  for (std::size_t i = 0; i < p.size(); i += 3)
    if (take(rng))
      out.insert(out.end(), p.begin() + i, p.begin() + i + 3);
  return out;
}

TEST(Robustness, LatticesUpTo50Cubed)
{
  for (int k : {4, 7, 16, 50})
    expectExactDelaunay(fd3test::lattice(k), "lattice " + std::to_string(k));
}

TEST(Robustness, RandomSubsetsOfLattices)
{
  for (double keep : {0.1, 0.5, 0.9})
    expectExactDelaunay(
      subset(fd3test::lattice(15), keep, 3), "lattice subset " + std::to_string(keep));
}

TEST(Robustness, PointsExactlyOnASphere)
{
  const Points p = fd3test::exactSphere(20000, 5);
  ASSERT_EQ(p.size(), 3u * 20000);
  const fd3::Triangulation r = expectExactDelaunay(p, "sphere");
  EXPECT_GT(r.stats.symbolicTies, 0u);
  // The perturbation pulls every tetrahedron to the first vertex: about 2 per point.
  EXPECT_LT(r.stats.tetrahedra, 3u * 20000);
}

TEST(Robustness, PointsExactlyOnAFewPlanes)
{
  // Three orthogonal planes through a unit cube and one slanted plane x + y + z = 1, on a grid
  // of step 1/64: exact in binary, so coplanarity is exact.
  Points p;
  std::mt19937_64 rng(8);
  std::uniform_int_distribution<int> g(0, 64);
  for (int i = 0; i < 3000; ++i)
  {
    const double a = g(rng) / 64.0, b = g(rng) / 64.0;
    switch (i % 4)
    {
      case 0:
        p.insert(p.end(), {a, b, 0.0});
        break;
      case 1:
        p.insert(p.end(), {a, 0.0, b});
        break;
      case 2:
        p.insert(p.end(), {0.0, a, b});
        break;
      default:
        p.insert(p.end(), {a / 2, b / 2, 1.0 - a / 2 - b / 2});
        break;
    }
  }
  expectExactDelaunay(p, "planes");
}

TEST(Robustness, CocircularAndCosphericalSubsets)
{
  // Clusters of cospherical points (integer sphere points, scaled and shifted by powers of two so
  // they stay exact) inside random points, and cocircular rings (z = const slices of the sphere).
  Points p = fd3test::uniformCube(2000, 4);
  const Points sphere = fd3test::exactSphere(400, 6);
  double radius = 0;
  for (double x : sphere)
    radius = std::max(radius, std::fabs(x));
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < sphere.size(); i += 3)
      for (int a = 0; a < 3; ++a)
        p.push_back(
          0.25 + 0.25 * c + std::ldexp(sphere[i + a], -2 - static_cast<int>(std::log2(radius))));
  for (int ring = 0; ring < 5; ++ring)
    for (int k = 0; k < 4; ++k)
    {
      // (3,4), (4,3), (5,0), (0,5) and their signs lie on the circle of radius 5.
      static const double circle[8][2] = {
        {3, 4}, {4, 3}, {5, 0}, {0, 5}, {-3, 4}, {-4, -3}, {-5, 0}, {0, -5}};
      for (const auto& c : circle)
        p.insert(p.end(), {2 + c[0] / 64 + k, 2 + c[1] / 64, ring / 8.0});
    }
  expectExactDelaunay(p, "cospherical and cocircular subsets");
}

TEST(Robustness, LinePlusOnePointIsDegenerate)
{
  Points p;
  for (int i = 0; i < 20; ++i)
    p.insert(p.end(), {i * 0.5, i * 0.25, i * 0.125});
  p.insert(p.end(), {0.0, 1.0, 0.0});
  const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3);
  EXPECT_EQ(r.status, fd3::Status::Degenerate); // a line and a point span a plane
  EXPECT_TRUE(r.tetrahedra.empty());
  p.insert(p.end(), {0.0, 0.0, 1.0}); // one more point off that plane: now a real triangulation
  expectExactDelaunay(p, "line plus two points");
}

// All configurations of up to 10 points drawn from a 3x3x3 lattice (collinear, coplanar,
// cospherical, duplicated), many random draws of each size.
TEST(Robustness, EverySmallConfiguration)
{
  const Points grid = fd3test::lattice(3);
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<int> pick(0, 26);
  for (std::size_t n = 1; n <= 10; ++n)
    for (int draw = 0; draw < 300; ++draw)
    {
      Points p;
      for (std::size_t i = 0; i < n; ++i)
      {
        const int k = pick(rng);
        p.insert(p.end(), grid.begin() + 3 * k, grid.begin() + 3 * k + 3);
      }
      const fd3::Triangulation r = fd3::triangulate(p.data(), n);
      if (r.status != fd3::Status::Ok)
      {
        ASSERT_TRUE(r.status == fd3::Status::TooFewPoints || r.status == fd3::Status::Degenerate);
        continue;
      }
      const auto report = fd3test::checkTriangulation(p.data(), n, r.tetrahedra);
      ASSERT_TRUE(report.valid()) << "n = " << n << " draw " << draw << ": " << report.summary();
    }
}

TEST(Robustness, TenAndNinetyPercentDuplicates)
{
  for (double share : {0.1, 0.9})
  {
    const Points base = fd3test::uniformBall(2000, 7);
    std::mt19937_64 rng(1);
    std::uniform_int_distribution<std::size_t> pick(0, 1999);
    Points p = base;
    const std::size_t copies = static_cast<std::size_t>(2000 * share / (1 - share));
    for (std::size_t i = 0; i < copies; ++i)
    {
      const std::size_t k = pick(rng);
      p.insert(p.end(), base.begin() + 3 * k, base.begin() + 3 * k + 3);
    }
    const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3);
    ASSERT_EQ(r.status, fd3::Status::Ok);
    EXPECT_EQ(r.stats.duplicatesMerged, copies);
    EXPECT_EQ(r.stats.insertedPoints, 2000u);
    expectExactDelaunay(p, "duplicates");
  }
}

TEST(Robustness, PointsThatDifferInTheLastBit)
{
  Points p = fd3test::uniformCube(500, 9);
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; i += 3)
    for (int a = 0; a < 3; ++a)
      p.push_back(std::nextafter(p[i + a], 2.0)); // a twin one ulp away on every axis
  expectExactDelaunay(p, "one-ulp twins");
}

TEST(Robustness, ThinSlabsAndTightClusters)
{
  expectExactDelaunay(fd3test::thinSlab(5000, 1e-9, 2), "slab 1e-9");
  expectExactDelaunay(fd3test::clusters(5000, 5, 1e-12, 3), "clusters of spread 1e-12");
}

// Scaling by a power of two and an exact shift keep every predicate's sign: huge, tiny and
// far-from-origin coordinates give exact results, and lattices there still hit the exact path.
TEST(Robustness, HugeTinyAndFarFromTheOrigin)
{
  for (double scale : {1e-300, 1e300})
  {
    Points p = joined(fd3test::uniformCube(2000, 10), fd3test::lattice(4));
    for (double& x : p)
      x *= scale;
    expectExactDelaunay(p, "scale " + std::to_string(scale));
  }
  Points far = fd3test::uniformCube(2000, 11);
  for (double& x : far)
    x += 1e9;
  expectExactDelaunay(far, "offset 1e9");
  Points lattice = fd3test::lattice(5);
  for (double& x : lattice)
    x = 1e9 + x * 0.25;
  EXPECT_GT(expectExactDelaunay(lattice, "lattice at 1e9").stats.symbolicTies, 0u);
}

// Magnitudes that no scaled frame holds exactly, each once on one thread and once on two.
void expectExactAtAnyThreads(const Points& p, const std::string& what)
{
  for (int threads : {1, 2})
    expectExactDelaunay(p, what + ", " + std::to_string(threads) + " threads", threads);
}

TEST(Robustness, SpansBeyondDoubleMax)
{
  const double big = DBL_MAX;
  Points corners;
  for (int k = 0; k < 8; ++k)
    corners.insert(corners.end(), {k & 1 ? big : -big, k & 2 ? big : -big, k & 4 ? big : -big});
  expectExactAtAnyThreads(joined(corners, fd3test::uniformCube(300, 21)), "corners at DBL_MAX");
  expectExactAtAnyThreads(
    scaled(fd3test::uniformCube(2000, 22), 1.78e308, -8.9e307), "within 9e307");
}

TEST(Robustness, TinyAndSubnormalSets)
{
  expectExactAtAnyThreads(scaled(fd3test::uniformCube(1000, 23), 1e-306), "within 1e-306");
  expectExactAtAnyThreads(scaled(fd3test::uniformCube(500, 24), 1e-310), "subnormal");
  // Multiples of the smallest subnormal: exact ties, all of them on the integer grid.
  expectExactAtAnyThreads(scaled(fd3test::lattice(6), 0x1p-1074), "lattice of 2^-1074");
}

TEST(Robustness, OneOutlierBesideUnitData)
{
  for (double far : {1e100, 1e200, DBL_MAX})
  {
    const Points outlier = {far, 0, 0};
    expectExactAtAnyThreads(
      joined(fd3test::uniformCube(1000, 25), outlier), "outlier " + std::to_string(far));
    expectExactAtAnyThreads(joined(fd3test::uniformCube(100, 25), outlier), "100 and outlier");
    expectExactAtAnyThreads(
      joined(fd3test::uniformCube(1000, 26), {-far, -far, far}), "corner outlier");
  }
}

// A cluster away from 0 would collapse onto one double: 0.5 + 1e-70 is 0.5. At 0, in the middle of
// unit data and at its corner.
TEST(Robustness, TinyClustersBesideUnitData)
{
  for (double spread : {1e-70, 1e-150, 1e-250})
  {
    const Points cluster = scaled(fd3test::uniformCube(300, 27), spread);
    const Points centred = scaled(fd3test::uniformCube(300, 28), 1, -0.5);
    expectExactAtAnyThreads(
      joined(centred, cluster), "cluster " + std::to_string(spread) + " inside");
    expectExactAtAnyThreads(joined(fd3test::uniformCube(300, 30), cluster), "cluster at a corner");
  }
}

} // namespace
