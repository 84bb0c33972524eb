// The kernel end to end, every result checked by the independent exact validator.
#include "CoreTestUtilities.h"
#include "ExactValidator.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>
#include <stdexcept>
#if defined(__linux__)
#include <unistd.h>
#endif

namespace
{
using fd3test::Points;

using fd3test::triangulateAndCheck;

#if defined(__linux__)
std::size_t residentBytes()
{
  std::ifstream statm("/proc/self/statm");
  std::size_t total = 0, resident = 0;
  statm >> total >> resident;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}
#endif

// The output's tetrahedra are compacted into the front of the mesh's records: the rest is given
// back, the tetrahedra stay, and the array can grow again.
TEST(BulkAllocator, SpareCapacityIsGivenBackAndTheElementsStay)
{
  constexpr std::size_t kWords = std::size_t(16) << 20; // 64 MB
  fd3::IdArray ids(kWords);
  std::iota(ids.begin(), ids.end(), 0u);
  ids.resize(kWords / 8);
#if defined(__linux__)
  const std::size_t before = residentBytes();
#endif
  fd3::releaseSpareCapacity(ids);
#if defined(__linux__)
  EXPECT_GT(before, residentBytes() + 3 * kWords) << "most of the 56 MB beyond the size given back";
#endif
  for (std::size_t i = 0; i < ids.size(); ++i)
    ASSERT_EQ(ids[i], i);
  ids.resize(kWords, 7u);
  EXPECT_EQ(ids[kWords / 8 - 1], kWords / 8 - 1);
  EXPECT_EQ(ids.back(), 7u);
}

TEST(Triangulate, UniformPoints)
{
  for (std::size_t n : {100u, 5000u})
  {
    const auto r = triangulateAndCheck(fd3test::uniformCube(n, 1));
    EXPECT_GT(r.stats.tetrahedra, 5 * n); // about 6.3-6.7 per point for uniform points
    EXPECT_LT(r.stats.tetrahedra, 7 * n);
  }
}

TEST(Triangulate, LatticeIsFullOfTies)
{
  for (int k : {2, 3, 5, 10})
  {
    const auto r = triangulateAndCheck(fd3test::lattice(k));
    // The 8 corners of every unit cube are cospherical with nothing inside their sphere, so each
    // cube is triangulated on its own, into 5 or 6 tetrahedra.
    const std::size_t cubes = std::size_t(k - 1) * (k - 1) * (k - 1);
    EXPECT_GE(r.stats.tetrahedra, 5 * cubes);
    EXPECT_LE(r.stats.tetrahedra, 6 * cubes);
    if (k > 2)
      EXPECT_GT(r.stats.symbolicTies, 0u);
  }
}

// Every point set of the benchmark (volume, surface, scan, terrain, lattice, exact sphere), exactly
// Delaunay, with a short walk.
TEST(Triangulate, EveryBenchmarkPointSet)
{
  for (const std::string& kind : fd3test::pointSetNames())
  {
    SCOPED_TRACE(kind);
    const auto r = triangulateAndCheck(fd3test::generate(kind, 10000, 2));
    EXPECT_LE(r.stats.meanWalk(), 12.0);
  }
}

// The structured and degenerate surface samples at a larger size: exact ties everywhere
// (cospherical rings and grid faces, coplanar layers), none on a small integer grid.
TEST(Triangulate, StructuredSetsAtScale)
{
#ifdef NDEBUG
  constexpr std::size_t kPoints = 100000;
#else
  constexpr std::size_t kPoints = 10000; // the sanitizers' build
#endif
  for (const char* kind :
    {"boxboundary", "revolution", "extrusion", "planes", "latlong", "ellipsoid"})
  {
    SCOPED_TRACE(kind);
    const Points p = fd3test::generate(kind, kPoints, 3);
    EXPECT_GT(p.size() / 3, kPoints * 9 / 10);
    triangulateAndCheck(p);
  }
}

TEST(Triangulate, DuplicatesAreMergedAndCounted)
{
  Points p = fd3test::uniformCube(1000, 5);
  const Points copy(p.begin(), p.begin() + 3 * 300); // 300 duplicates
  p.insert(p.end(), copy.begin(), copy.end());
  p.insert(p.end(), copy.begin(), copy.begin() + 3 * 10); // 10 triplicates
  const auto r = triangulateAndCheck(p);
  EXPECT_EQ(r.stats.duplicatesMerged, 310u);
  EXPECT_EQ(r.stats.insertedPoints, 1000u);
  for (std::size_t i = 1000; i < 1310; ++i)
  {
    const std::uint32_t rep = r.representative[i];
    ASSERT_LT(rep, p.size() / 3);
    EXPECT_EQ(p[3 * rep], p[3 * i]);
    EXPECT_EQ(p[3 * rep + 1], p[3 * i + 1]);
    EXPECT_EQ(p[3 * rep + 2], p[3 * i + 2]);
  }
}

// Every count from 1 to 10, in general position and on the unit-cube lattice (degenerate).
TEST(Triangulate, EveryCountFromOneToTen)
{
  const Points cube = fd3test::lattice(3);
  for (std::size_t n = 1; n <= 10; ++n)
  {
    const Points random = fd3test::uniformCube(10, 11 + n);
    for (const Points* source : {&random, &cube})
    {
      const Points p(source->begin(), source->begin() + 3 * n);
      const fd3::Triangulation r = fd3::triangulate(p.data(), n);
      if (n < 4)
      {
        EXPECT_EQ(r.status, fd3::Status::TooFewPoints);
        EXPECT_TRUE(r.tetrahedra.empty());
        continue;
      }
      // The first lattice points (0,0,0),(0,0,1),(0,0,2),(0,1,0)... are coplanar up to n = 9.
      const bool coplanar = source == &cube && n <= 9;
      if (coplanar)
      {
        EXPECT_EQ(r.status, fd3::Status::Degenerate);
        EXPECT_TRUE(r.tetrahedra.empty());
        continue;
      }
      ASSERT_EQ(r.status, fd3::Status::Ok);
      const auto report = fd3test::checkTriangulation(p.data(), n, r.tetrahedra);
      EXPECT_TRUE(report.valid()) << "n = " << n << ": " << report.summary();
    }
  }
}

// Ties are broken by a key that each point's coordinates decide, so the tetrahedra depend on the
// point set alone: the same for every insertion order and for the input in any order, lattices and
// cospherical points included (what lets MPI ranks agree with a single process).
TEST(Triangulate, SameTetrahedraForAnyOrderEvenWithTies)
{
  for (const char* kind : {"lattice", "sphere", "terrain"})
  {
    SCOPED_TRACE(kind);
    const Points p = fd3test::generate(kind, 20000, 3);
    const std::size_t n = p.size() / 3;
    // The same points, shuffled: tetrahedra are compared by the points' coordinates.
    std::vector<std::uint32_t> permutation(n);
    std::iota(permutation.begin(), permutation.end(), 0u);
    std::shuffle(permutation.begin(), permutation.end(), std::mt19937(5));
    Points shuffled(p.size());
    for (std::size_t i = 0; i < n; ++i)
      std::copy_n(&p[3 * permutation[i]], 3, &shuffled[3 * i]);
    auto byCoordinates = [](const Points& xyz, const fd3::IdArray& tets) {
      std::vector<std::array<std::array<double, 3>, 4>> out(tets.size() / 4);
      for (std::size_t t = 0; t < out.size(); ++t)
      {
        for (int k = 0; k < 4; ++k)
          std::copy_n(&xyz[3 * tets[4 * t + k]], 3, out[t][k].begin());
        std::sort(out[t].begin(), out[t].end());
      }
      std::sort(out.begin(), out.end());
      return out;
    };
    fd3::Options options;
    const auto reference = byCoordinates(p, triangulateAndCheck(p, options).tetrahedra);
    EXPECT_EQ(
      byCoordinates(shuffled, triangulateAndCheck(shuffled, options).tetrahedra), reference);
    options.order = fd3::InsertionOrder::Input;
    EXPECT_EQ(byCoordinates(p, triangulateAndCheck(p, options).tetrahedra), reference);
    options.order = fd3::InsertionOrder::Random;
    EXPECT_EQ(byCoordinates(p, triangulateAndCheck(p, options).tetrahedra), reference);
  }
}

TEST(Triangulate, InsertionOrdersAgreeOnGeneralPosition)
{
  // In general position the Delaunay triangulation is unique: every order must find it.
  const Points p = fd3test::uniformBall(2000, 9);
  auto sorted = [](const fd3::IdArray& tets) { return fd3test::canonicalTetrahedra(tets); };
  fd3::Options options;
  const auto brio = sorted(triangulateAndCheck(p, options).tetrahedra);
  options.order = fd3::InsertionOrder::Input;
  options.pointsPerCell = 0;
  EXPECT_EQ(sorted(triangulateAndCheck(p, options).tetrahedra), brio);
  options.order = fd3::InsertionOrder::Random;
  options.pointsPerCell = 8;
  EXPECT_EQ(sorted(triangulateAndCheck(p, options).tetrahedra), brio);
}

// The centre of points on a sphere, inserted last, is in conflict with almost every tetrahedron:
// its cavity's boundary is the whole hull, too many vertices for the edge table of fillCavity, so
// the new tetrahedra are linked by rotation about the boundary's edges instead.
TEST(Triangulate, HugeCavityIsLinkedByRotation)
{
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal;
  Points p;
  // More than the table's 512 local numbers: with 400 points, it took the whole hull.
  for (int i = 0; i < 700; ++i)
  {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    const double r = std::sqrt(x * x + y * y + z * z);
    p.insert(p.end(), {x / r, y / r, z / r});
  }
  p.insert(p.end(), {0.0, 0.0, 0.0});
  fd3::Options options;
  options.order = fd3::InsertionOrder::Input;
  const auto r = triangulateAndCheck(p, options);
  EXPECT_EQ(r.stats.insertedPoints, 701u);
  EXPECT_GT(r.stats.cavityTetrahedra, 2 * 700u) << "the centre's cavity should hold the whole ball";
}

// Tolerance keeps points at least `tolerance` apart, each skipped point close to the vertex it was
// skipped for, whatever the thread count; the kept points are exactly triangulated.
TEST(Triangulate, ToleranceSkipsOnlyClosePoints)
{
  const Points p = fd3test::clusters(30000, 20, 1e-3, 9);
  const std::size_t n = p.size() / 3;
  const double tolerance = 2e-4;
  auto distance = [&](std::uint32_t a, std::uint32_t b) {
    const double dx = p[3 * a] - p[3 * b], dy = p[3 * a + 1] - p[3 * b + 1],
                 dz = p[3 * a + 2] - p[3 * b + 2];
    return std::sqrt(dx * dx + dy * dy + dz * dz);
  };
  std::vector<std::array<std::uint32_t, 4>> reference;
  for (int threads : {1, 2})
  {
    fd3::Options options;
    options.tolerance = tolerance;
    options.threads = threads;
    const fd3::Triangulation r = fd3::triangulate(p.data(), n, options);
    ASSERT_EQ(r.status, fd3::Status::Ok);
    EXPECT_GT(r.stats.closePointsSkipped, n / 2);
    EXPECT_EQ(r.stats.insertedPoints + r.stats.closePointsSkipped, n);
    std::vector<std::uint32_t> kept;
    for (std::uint32_t i = 0; i < n; ++i)
    {
      if (r.representative[i] == i)
        kept.push_back(i);
      else
        ASSERT_LT(distance(i, r.representative[i]), tolerance) << "point " << i;
    }
    ASSERT_EQ(kept.size(), r.stats.insertedPoints);
    // Kept points are tolerance apart: checked among neighbours in x (sorted), which suffices.
    std::sort(kept.begin(), kept.end(), [&](auto a, auto b) { return p[3 * a] < p[3 * b]; });
    for (std::size_t i = 0; i < kept.size(); ++i)
      for (std::size_t j = i + 1; j < kept.size() && p[3 * kept[j]] - p[3 * kept[i]] < tolerance;
           ++j)
        ASSERT_GE(distance(kept[i], kept[j]), tolerance);
    fd3test::ValidityOptions validity;
    Points keptPoints;
    for (std::uint32_t i = 0; i < n; ++i)
      keptPoints.insert(
        keptPoints.end(), {r.representative[i] == i ? p[3 * i] : NAN, p[3 * i + 1], p[3 * i + 2]});
    const auto report = fd3test::checkTriangulation(keptPoints.data(), n, r.tetrahedra, validity);
    EXPECT_TRUE(report.valid()) << report.summary();
    if (threads == 1)
      reference = fd3test::canonicalTetrahedra(r.tetrahedra);
    else
      EXPECT_EQ(fd3test::canonicalTetrahedra(r.tetrahedra), reference);
  }
}

TEST(Triangulate, NeighboursAreConsistent)
{
  const Points p = fd3test::uniformCube(3000, 21);
  const auto r = triangulateAndCheck(p);
  std::size_t hull = 0;
  for (std::size_t code = 0; code < r.neighbors.size(); ++code)
  {
    const std::uint32_t back = r.neighbors[code];
    if (back == fd3::kNoNeighbor)
    {
      ++hull;
      continue;
    }
    ASSERT_EQ(r.neighbors[back], code);
  }
  EXPECT_GT(hull, 0u);
}

TEST(Triangulate, NonFinitePointsAreSkippedAndCounted)
{
  Points p = fd3test::uniformCube(200, 4);
  p[3 * 7] = std::nan("");
  p[3 * 50 + 2] = INFINITY;
  const auto r = triangulateAndCheck(p);
  EXPECT_EQ(r.stats.nonFinitePoints, 2u);
  EXPECT_EQ(r.representative[7], fd3::kNoPoint);
}

// The sliver guard gives up the Delaunay property, never validity: the output stays a
// triangulation of the hull using every point, on every kind of input.
TEST(Triangulate, VolumeThresholdKeepsAValidTriangulation)
{
  for (const char* kind : {"cube", "lattice", "sphere", "clusters", "slab", "torus"})
  {
    const Points p = fd3test::generate(kind, 3000, 17);
    const std::size_t n = p.size() / 3;
    for (double threshold : {0.05, 0.2})
    {
      fd3::Options options;
      options.volumeThreshold = threshold;
      const fd3::Triangulation guarded = fd3::triangulate(p.data(), n, options);
      ASSERT_EQ(guarded.status, fd3::Status::Ok);
      fd3test::ValidityOptions validity;
      validity.requireDelaunay = false;
      const auto report = fd3test::checkTriangulation(p.data(), n, guarded.tetrahedra, validity);
      EXPECT_TRUE(report.valid()) << kind << " threshold " << threshold << ": " << report.summary();
      EXPECT_EQ(report.usedVertices, report.distinctPoints) << kind;
    }
  }
}

// A failure in the middle of a run: the exception crosses the kernel, which releases everything
// (LeakSanitizer checks in the sanitizer build), and the next run is correct.
TEST(Triangulate, ExceptionMidRunLeavesNothingBehind)
{
  const Points p = fd3test::uniformCube(40000, 3);
  fd3::Options options;
  options.progress = [](double fraction) -> bool {
    if (fraction > 0.3)
      throw std::runtime_error("simulated failure");
    return true;
  };
  EXPECT_THROW(fd3::triangulate(p.data(), p.size() / 3, options), std::runtime_error);
  triangulateAndCheck(p);
}

TEST(Triangulate, AbortStopsAndReportsIt)
{
  const Points p = fd3test::uniformCube(40000, 2);
  fd3::Options options;
  options.progress = [](double) { return false; };
  const auto r = fd3::triangulate(p.data(), p.size() / 3, options);
  EXPECT_EQ(r.status, fd3::Status::Aborted);
  EXPECT_TRUE(r.tetrahedra.empty());
}

} // namespace
