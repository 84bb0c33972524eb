// Weighted points in a periodic box: the periodic regular tetrahedralization decided by the exact
// periodic validator (locally regular faces across the box, hidden points truly hidden, every
// periodic tetrahedron once), on uniform points with random radii, lattices with equal and
// alternating weights (ties across the faces), a packing with a quarter hidden, heavy points whose
// balls reach across the box, a slab, points outside the box and any thread count; then the
// periodic power cells against Voro++'s periodic radical container.
#include "PeriodicTestUtilities.h"
#include "PointSets.h"
#include "fd3/Periodic.h"
#ifdef FD3_TEST_WITH_VOROPP
#include "VoroppVolumes.h"
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace
{
using fd3test::canonical;
using fd3test::domainOf;
using fd3test::Points;
using fd3test::randomWeights;
using fd3test::sum;
using fd3test::tetrahedraOf;

/// The periodic regular tetrahedralization of p with weights w in box, checked by the validator
/// and by its own figures: every finite point a vertex, hidden, or an equal-weight copy.
fd3::PeriodicTriangulation checked(const Points& p, const std::vector<double>& w,
  const fd3::PeriodicBox& box, const std::string& what, const fd3::Options& options = {})
{
  const std::size_t n = p.size() / 3;
  const fd3::PeriodicTriangulation t =
    fd3::triangulatePeriodic(p.data(), w.data(), n, box, options);
  EXPECT_EQ(t.status, fd3::Status::Ok) << what;
  fd3test::ValidityOptions check;
  check.weights = w.data();
  check.hidden = t.hidden;
  const fd3test::ValidityReport report =
    fd3test::checkPeriodicTriangulation(p.data(), n, domainOf(box), tetrahedraOf(t), check);
  EXPECT_TRUE(report.valid()) << what << ": " << report.summary();
  const fd3::Statistics& s = t.stats;
  EXPECT_EQ(s.insertedPoints, report.usedVertices) << what;
  EXPECT_EQ(s.hiddenPoints, t.hidden.size()) << what;
  EXPECT_EQ(s.insertedPoints + s.hiddenPoints + s.duplicatesMerged + s.nonFinitePoints, n) << what;
  EXPECT_EQ(s.tetrahedra, t.numberOfTetrahedra()) << what;
  for (const std::uint32_t h : t.hidden)
    EXPECT_EQ(t.representative[h], h) << what;
  return t;
}

/// A k^3 lattice of the given spacing from the origin, and alternating weights on it (0 and
/// `weight`, as a rock-salt crystal's two ions).
Points cubicLattice(int k, double spacing, std::vector<double>& alternating, double weight)
{
  Points p;
  alternating.clear();
  for (int x = 0; x < k; ++x)
    for (int y = 0; y < k; ++y)
      for (int z = 0; z < k; ++z)
      {
        p.insert(p.end(), {x * spacing, y * spacing, z * spacing});
        alternating.push_back((x + y + z) % 2 ? weight : 0.0);
      }
  return p;
}

TEST(PeriodicWeighted, UniformPointsWithRandomRadii)
{
  const Points p = fd3test::uniformCube(3000, 41);
  const std::vector<double> w = randomWeights(3000, 0.0, 0.05, 42);
  const auto t = checked(p, w, fd3::PeriodicBox(), "uniform");
  EXPECT_GT(t.numberOfTetrahedra(), 5 * 3000u);
  EXPECT_GT(t.imagePoints, 0u);
}

// The validator's weighted checks fail where they must: the Delaunay tetrahedra are not regular
// for unequal weights, a hidden point left unlisted is no vertex, and a vertex listed hidden is
// one; a hidden point listed beside a repeat of it that is a vertex is not hidden.
TEST(PeriodicWeighted, ValidatorCatchesDamage)
{
  const Points p = fd3test::uniformCube(600, 57);
  const std::vector<double> w = randomWeights(600, 0.0, 0.08, 58);
  const fd3::PeriodicTriangulation t =
    fd3::triangulatePeriodic(p.data(), w.data(), 600, fd3::PeriodicBox());
  ASSERT_EQ(t.status, fd3::Status::Ok);
  ASSERT_FALSE(t.hidden.empty());
  fd3test::ValidityOptions check;
  check.weights = w.data();
  check.hidden = t.hidden;
  const auto domain = domainOf(fd3::PeriodicBox());
  EXPECT_TRUE(
    fd3test::checkPeriodicTriangulation(p.data(), 600, domain, tetrahedraOf(t), check).valid());

  const fd3::PeriodicTriangulation plain =
    fd3::triangulatePeriodic(p.data(), 600, fd3::PeriodicBox());
  check.hidden.clear();
  const auto notRegular =
    fd3test::checkPeriodicTriangulation(p.data(), 600, domain, tetrahedraOf(plain), check);
  EXPECT_FALSE(notRegular.valid());
  EXPECT_NE(notRegular.summary().find("not locally regular"), std::string::npos);

  check.hidden.assign(t.hidden.begin() + 1, t.hidden.end());
  EXPECT_FALSE(
    fd3test::checkPeriodicTriangulation(p.data(), 600, domain, tetrahedraOf(t), check).valid());

  check.hidden = t.hidden;
  const std::uint32_t vertex = t.tetrahedra[0];
  check.hidden.push_back(vertex);
  const auto listed =
    fd3test::checkPeriodicTriangulation(p.data(), 600, domain, tetrahedraOf(t), check);
  EXPECT_FALSE(listed.valid());
  EXPECT_NE(listed.summary().find("hidden point " + std::to_string(vertex) + " is a vertex"),
    std::string::npos);

  // A repeat of a vertex with its weight, listed hidden.
  Points more = p;
  std::vector<double> heavier = w;
  more.insert(more.end(), p.begin() + 3 * vertex, p.begin() + 3 * vertex + 3);
  heavier.push_back(w[vertex]);
  check.weights = heavier.data();
  check.hidden = t.hidden;
  check.hidden.push_back(600);
  const auto copy =
    fd3test::checkPeriodicTriangulation(more.data(), 601, domain, tetrahedraOf(t), check);
  EXPECT_FALSE(copy.valid()) << "an equal-weight repeat of a vertex is a duplicate, not hidden";
}

TEST(PeriodicWeighted, EqualWeightsGiveTheDelaunayTetrahedraBitForBit)
{
  const Points p = fd3test::uniformCube(2000, 43);
  const std::vector<double> w(2000, 0.01);
  const auto weighted = checked(p, w, fd3::PeriodicBox(), "equal weights");
  const auto plain = fd3::triangulatePeriodic(p.data(), 2000, fd3::PeriodicBox());
  EXPECT_TRUE(weighted.tetrahedra == plain.tetrahedra);
  EXPECT_TRUE(weighted.offsets == plain.offsets);
  EXPECT_TRUE(weighted.hidden.empty());
}

// A lattice commensurate with the box: ties across its faces, with equal weights and with
// alternating ones (a shift of 1/7 makes images that no double holds).
TEST(PeriodicWeighted, LatticeWithEqualAndAlternatingWeights)
{
  std::vector<double> alternating;
  const Points p = cubicLattice(6, 1.0 / 6, alternating, 0.002);
  const std::vector<double> equal(p.size() / 3, 0.002);
  checked(p, equal, fd3::PeriodicBox(), "lattice, equal");
  const auto t = checked(p, alternating, fd3::PeriodicBox(), "lattice, alternating");
  EXPECT_GT(t.stats.symbolicTies, 0u);
  Points shifted = p;
  for (double& x : shifted)
    x += 1.0 / 7;
  checked(shifted, alternating, fd3::PeriodicBox(), "lattice, alternating, shifted");
}

// Balls of radius 0.1 and, a quarter of the points, balls of 0.001 deep inside them, some a
// period outside the box.
TEST(PeriodicWeighted, PackingWithAQuarterHidden)
{
  const std::size_t large = 1500, small = 500;
  Points p = fd3test::uniformCube(large, 44);
  std::vector<double> w(large, 0.01);
  std::mt19937_64 random(45);
  std::uniform_real_distribution<double> offset(-0.005, 0.005);
  std::uniform_int_distribution<std::size_t> pick(0, large - 1);
  for (std::size_t i = 0; i < small; ++i)
  {
    const std::size_t c = pick(random);
    for (int k = 0; k < 3; ++k)
      p.push_back(p[3 * c + k] + offset(random) + (i % 3 == 0 ? 1.0 : 0.0));
    w.push_back(1e-6);
  }
  const auto t = checked(p, w, fd3::PeriodicBox(), "packing");
  EXPECT_GE(t.hidden.size(), 450u);
}

// Heavy points whose balls reach across the box, among light ones: the image of the first, a
// quarter of a period outside the box, beyond the first shell of images, hides points in the box
// that the point itself does not reach. The covering widens with the weights' spread. Then a
// handful of weighted points in a large box.
TEST(PeriodicWeighted, HeavyPointsAndAHandfulOfPoints)
{
  Points p = fd3test::uniformCube(3000, 46);
  std::vector<double> w(3000, 0.0);
  p.insert(p.end(), {0.75, 0.5, 0.5, 0.05, 0.95, 0.5});
  w.push_back(0.45 * 0.45);
  w.push_back(0.2);
  const auto heavy = checked(p, w, fd3::PeriodicBox(), "heavy");
  const double* image = p.data() + 3 * 3000;
  std::size_t acrossOnly = 0; // hidden points that only the image's ball reaches
  for (const std::uint32_t h : heavy.hidden)
  {
    const double* q = p.data() + 3 * std::size_t(h);
    auto distance2 = [&](double shift) {
      return (q[0] - image[0] - shift) * (q[0] - image[0] - shift) +
        (q[1] - image[1]) * (q[1] - image[1]) + (q[2] - image[2]) * (q[2] - image[2]);
    };
    acrossOnly += distance2(-1.0) < 0.45 * 0.45 && distance2(0.0) > 0.45 * 0.45;
  }
  EXPECT_GT(acrossOnly, 10u);
  EXPECT_FALSE(std::binary_search(heavy.hidden.begin(), heavy.hidden.end(), 3000u));

  fd3::PeriodicBox large;
  std::fill(large.hi, large.hi + 3, 10.0);
  const Points few = {1, 2, 3, 7, 1, 5, 4, 8, 2, 9, 9, 9, 5, 5, 0.5};
  checked(few, {1.0, 4.0, 0.0, 2.0, 9.0}, large, "five points in a large box");
  checked({3, 3, 3}, {2.0}, large, "one point");
}

// One point whose ball spans periods among light ones: its images come from afar, the light
// points' from the usual shell (not every point's images as far as the heavy one reaches). A
// reach beyond four periods is refused.
TEST(PeriodicWeighted, OneHeavyPointAmongLightOnes)
{
  Points p = fd3test::uniformCube(1000, 65);
  std::vector<double> w(1000, 0.0);
  w[0] = 3.0; // a reach of sqrt(3) periods
  w[1] = 0.01;
  const auto t = checked(p, w, fd3::PeriodicBox(), "one heavy point");
  EXPECT_EQ(t.hidden.size(), 999u); // the heavy point's images hide everything else
  EXPECT_LT(t.imagePoints, 20000u);

  w[0] = 17.0;
  const auto refused = fd3::triangulatePeriodic(p.data(), w.data(), 1000, fd3::PeriodicBox());
  EXPECT_EQ(refused.status, fd3::Status::OutOfRange);
  EXPECT_EQ(refused.numberOfTetrahedra(), 0u);
}

// Repeats once wrapped: of equal weights one is kept, the others merged; of unequal ones the
// heaviest is kept and the others hidden; an equal copy of a hidden point is merged into it.
TEST(PeriodicWeighted, RepeatsKeepTheHeaviest)
{
  Points p = fd3test::uniformCube(300, 59);
  std::vector<double> w = randomWeights(300, 0.0, 0.03, 60);
  std::copy_n(std::array<double, 3>{0.75, 0.5, 0.25}.begin(), 3, p.begin());
  p.insert(p.end(), {1.75, 0.5, -0.75}); // 300: point 0 a period away, of its weight
  w.push_back(w[0]);
  p.insert(p.end(), {p[3], p[4], p[5]}); // 301: point 1, lighter
  w.push_back(w[1] - 0.001);
  p.insert(p.end(), {p[6], p[7], p[8]}); // 302: point 2, heavier
  w.push_back(w[2] + 0.001);
  p.insert(p.end(), {p[9] + 0.001, p[10], p[11]}); // 303: a heavy point beside point 3
  w.push_back(0.05);
  p.insert(p.end(), {p[9], p[10], p[11]}); // 304: point 3 again, of its weight
  w.push_back(w[3]);
  const auto t = checked(p, w, fd3::PeriodicBox(), "repeats");
  EXPECT_EQ(t.stats.duplicatesMerged, 2u);
  EXPECT_EQ(t.representative[300], 0u);
  EXPECT_EQ(t.representative[304], 3u);
  for (const std::uint32_t hidden : {2u, 3u, 301u})
    EXPECT_TRUE(std::binary_search(t.hidden.begin(), t.hidden.end(), hidden)) << hidden;
  EXPECT_FALSE(std::binary_search(t.hidden.begin(), t.hidden.end(), 304u));
}

// Two points whose images across the box round to one record, of different weights: no weight
// decides between them, whose exact places differ; the later one is skipped, and said to be.
TEST(PeriodicWeighted, PointsTooCloseForTheBoxAreSkipped)
{
  Points p = fd3test::uniformCube(300, 61);
  std::vector<double> w = randomWeights(300, 0.0, 0.03, 62);
  std::copy_n(std::array<double, 3>{0x1p-60, 0.5, 0.25}.begin(), 3, p.begin());
  p.insert(p.end(), {0x1p-61, 0.5, 0.25}); // its image at 1 + 2^-61 rounds as 1 + 2^-60 does
  w.push_back(w[0] + 0.0001);
  const auto t = fd3::triangulatePeriodic(p.data(), w.data(), 301, fd3::PeriodicBox());
  ASSERT_EQ(t.status, fd3::Status::Ok);
  EXPECT_EQ(t.stats.closePointsSkipped, 1u);
  EXPECT_EQ(t.representative[300], 0u);
  EXPECT_FALSE(std::binary_search(t.hidden.begin(), t.hidden.end(), 300u));
  p.resize(900);
  w.resize(300);
  checked(p, w, fd3::PeriodicBox(), "without the close one");
}

// Negative weights (balls of imaginary radius): every weight shifted below 0, and a few points
// far lighter than the rest, which hide nothing and make no other point reach far.
TEST(PeriodicWeighted, NegativeWeights)
{
  const Points p = fd3test::uniformCube(2000, 63);
  std::vector<double> w = randomWeights(2000, 0.0, 0.04, 64);
  for (double& x : w)
    x -= 0.0008;
  const auto shifted = checked(p, w, fd3::PeriodicBox(), "negative weights");
  for (std::size_t i = 0; i < 2000; i += 400)
    w[i] = -20.0;
  const auto t = checked(p, w, fd3::PeriodicBox(), "a few far lighter");
  EXPECT_LT(t.imagePoints, shifted.imagePoints * 11 / 10);
  for (std::size_t i = 0; i < 2000; i += 400)
    EXPECT_TRUE(std::binary_search(t.hidden.begin(), t.hidden.end(), std::uint32_t(i))) << i;
}

// A slab periodic in x and y, and a few heavy points in it whose balls reach past the first
// shell: tetrahedra at the slab's surfaces have their balls outside it, which heavy points in it
// may still reach.
TEST(PeriodicWeighted, HeavyPointsInASlab)
{
  Points p = fd3test::uniformCube(2000, 66);
  for (std::size_t i = 2; i < p.size(); i += 3)
    p[i] *= 0.2;
  std::vector<double> w(2000, 0.0);
  for (std::size_t i = 0; i < 2000; i += 250)
    w[i] = 0.1;
  fd3::PeriodicBox box;
  box.periodic[2] = false;
  checked(p, w, box, "heavy points in a slab");
}

TEST(PeriodicWeighted, SlabPeriodicInTwoAxes)
{
  Points p = fd3test::uniformCube(2000, 47);
  for (std::size_t i = 2; i < p.size(); i += 3)
    p[i] *= 0.2;
  fd3::PeriodicBox box;
  box.periodic[2] = false;
  checked(p, randomWeights(2000, 0.0, 0.03, 48), box, "slab");
}

TEST(PeriodicWeighted, SameTetrahedraForAnyThreadCount)
{
  const Points p = fd3test::uniformCube(20000, 49);
  const std::vector<double> w = randomWeights(20000, 0.0, 0.02, 50);
  fd3::Options options;
  options.threads = 1;
  const auto one = fd3::triangulatePeriodic(p.data(), w.data(), 20000, fd3::PeriodicBox(), options);
  ASSERT_EQ(one.status, fd3::Status::Ok);
  for (const int threads : {2, 5})
  {
    options.threads = threads;
    const auto many =
      fd3::triangulatePeriodic(p.data(), w.data(), 20000, fd3::PeriodicBox(), options);
    EXPECT_EQ(canonical(many), canonical(one)) << threads;
    EXPECT_EQ(many.numberOfTetrahedra(), one.numberOfTetrahedra()) << threads;
    EXPECT_TRUE(many.hidden == one.hidden) << threads;
  }
}

TEST(PeriodicWeighted, NonFiniteWeightsAreLeftOut)
{
  Points p = fd3test::uniformCube(500, 51);
  std::vector<double> w = randomWeights(500, 0.0, 0.05, 52);
  w[7] = std::numeric_limits<double>::quiet_NaN();
  w[8] = HUGE_VAL;
  const auto t = checked(p, w, fd3::PeriodicBox(), "non-finite weights");
  EXPECT_EQ(t.stats.nonFinitePoints, 2u);
  EXPECT_EQ(t.representative[7], fd3::kNoPoint);
}

TEST(PeriodicWeighted, PowerCellsFillTheBoxAndHiddenPointsHaveNone)
{
  Points p = fd3test::uniformCube(1000, 53);
  std::vector<double> w = randomWeights(1000, 0.0, 0.05, 54);
  p.insert(p.end(), {0.5, 0.5, 0.5, 0.501, 0.5, 0.5});
  w.push_back(0.04);
  w.push_back(0.0); // deep inside the heavy ball beside it
  const fd3::VoronoiCells cells =
    fd3::voronoiCellsPeriodic(p.data(), w.data(), 1002, fd3::PeriodicBox());
  ASSERT_EQ(cells.status, fd3::Status::Ok);
  EXPECT_NEAR(sum(cells.volumes), 1.0, 1e-12);
  EXPECT_GE(cells.stats.hiddenPoints, 1u);
  const auto t = fd3::triangulatePeriodic(p.data(), w.data(), 1002, fd3::PeriodicBox());
  EXPECT_EQ(cells.stats.hiddenPoints, t.hidden.size());
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
    if (std::binary_search(t.hidden.begin(), t.hidden.end(), cells.generators[c]))
    {
      EXPECT_EQ(cells.numberOfFaces(c), 0u);
      EXPECT_EQ(cells.volumes[c], 0.0);
    }
}

#ifdef FD3_TEST_WITH_VOROPP
// Against Voro++'s periodic radical container (every axis periodic), to 1e-9 of each volume.
TEST(PeriodicWeighted, SameVolumesAsVoroppRadicalCells)
{
  const std::size_t n = 4000;
  const Points p = fd3test::uniformCube(n, 55);
  std::vector<double> radii(n);
  std::mt19937_64 random(56);
  std::uniform_real_distribution<double> radius(0.0, 0.04);
  for (double& r : radii)
    r = radius(random);
  std::vector<double> w(n);
  for (std::size_t i = 0; i < n; ++i)
    w[i] = radii[i] * radii[i];
  const fd3::VoronoiCells cells =
    fd3::voronoiCellsPeriodic(p.data(), w.data(), n, fd3::PeriodicBox());
  ASSERT_EQ(cells.status, fd3::Status::Ok);
  const int blocks = fd3test::voroppBlocks(n);
  voro::container_periodic_poly container(1, 0, 1, 0, 0, 1, blocks, blocks, blocks, 8);
  for (std::size_t i = 0; i < n; ++i)
    container.put(int(i), p[3 * i], p[3 * i + 1], p[3 * i + 2], radii[i]);
  const std::vector<double> expected =
    fd3test::voroppVolumes<voro::container_periodic_poly, voro::c_loop_all_periodic>(container, n);
  std::vector<double> volume(n, 0.0);
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
    volume[cells.generators[c]] = cells.volumes[c];
  for (std::size_t i = 0; i < n; ++i)
  {
    const double reference = std::max(expected[i], 0.0); // Voro++ makes no cell for a hidden one
    EXPECT_NEAR(volume[i], reference, 1e-9 * std::max(reference, 1e-6)) << i;
  }
  EXPECT_NEAR(sum(cells.volumes), 1.0, 1e-12);
}
#endif

} // namespace
