// The periodic tetrahedralization (fd3/Periodic.h), decided by the exact periodic validator:
// uniform points, lattices commensurate with the box (ties across its faces, with images that no
// double holds), a handful of points in a large box, slabs and columns, points outside the box,
// repeats, any thread count, and bad input; the tetrahedra placed for drawing, and the periodic
// density. Then the periodic Voronoi cells: their volumes fill the box and equal Voro++'s
// periodic containers'.
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
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace
{
using fd3test::canonical;
using fd3test::domainOf;
using fd3test::Points;
using fd3test::sum;
using fd3test::tetrahedraOf;

/// The periodic tetrahedralization of p in box, checked by the validator.
fd3::PeriodicTriangulation checked(
  const Points& p, const fd3::PeriodicBox& box, const fd3::Options& options = fd3::Options())
{
  const fd3::PeriodicTriangulation t =
    fd3::triangulatePeriodic(p.data(), p.size() / 3, box, options);
  EXPECT_EQ(t.status, fd3::Status::Ok);
  const auto report =
    fd3test::checkPeriodicTriangulation(p.data(), p.size() / 3, domainOf(box), tetrahedraOf(t));
  EXPECT_TRUE(report.valid()) << report.summary();
  EXPECT_EQ(t.stats.tetrahedra, t.numberOfTetrahedra());
  return t;
}

Points cubicLattice(int k, double spacing)
{
  Points p;
  for (int x = 0; x < k; ++x)
    for (int y = 0; y < k; ++y)
      for (int z = 0; z < k; ++z)
        p.insert(p.end(), {x * spacing, y * spacing, z * spacing});
  return p;
}

TEST(Periodic, UniformPoints)
{
  const Points p = fd3test::uniformCube(3000, 3);
  const auto t = checked(p, fd3::PeriodicBox());
  EXPECT_EQ(t.stats.insertedPoints, 3000u);
  EXPECT_GT(t.imagePoints, 0u);
  // Euler's relation on the 3-torus, V - E + F - T = 0 with F = 2T: every edge counted.
  EXPECT_GT(t.numberOfTetrahedra(), 6 * 3000u);
  EXPECT_LT(t.numberOfTetrahedra(), 7 * 3000u);
  EXPECT_GT(t.stats.secondsTotal, 0.0) << "the filters report it as KernelSeconds";
}

TEST(Periodic, SameTetrahedraForAnyThreadCount)
{
  const Points p = fd3test::uniformCube(20000, 4);
  fd3::Options options;
  options.threads = 1;
  const auto one = fd3::triangulatePeriodic(p.data(), 20000, fd3::PeriodicBox(), options);
  for (int threads : {2, 5, 16})
  {
    options.threads = threads;
    const auto many = fd3::triangulatePeriodic(p.data(), 20000, fd3::PeriodicBox(), options);
    EXPECT_EQ(canonical(many), canonical(one)) << threads;
    EXPECT_EQ(many.numberOfTetrahedra(), one.numberOfTetrahedra()) << threads;
  }
}

// Spacings 1/4 (images are doubles), 1/10 and 1/3 (images are not: 0.1 + 1 needs 57 bits): every
// cube of the lattice has eight cospherical corners, here and across the box's faces, and the
// perturbation must break them the same way in every copy.
TEST(Periodic, LatticesCommensurateWithTheBox)
{
  for (const auto& [k, spacing] : {std::pair<int, double>{4, 0.25}, {10, 0.1}, {3, 1.0 / 3}})
  {
    const Points p = cubicLattice(k, spacing);
    const auto t = checked(p, fd3::PeriodicBox());
    EXPECT_EQ(t.stats.insertedPoints, std::size_t(k * k * k)) << spacing;
  }
  // A lattice in a box that is not the unit one, and not at the origin.
  fd3::PeriodicBox box;
  for (int k = 0; k < 3; ++k)
  {
    box.lo[k] = -0.3;
    box.hi[k] = 0.9; // a period of 1.2: 6 spacings of 0.2
  }
  Points p = cubicLattice(6, 0.2);
  for (double& x : p)
    x -= 0.3;
  checked(p, box);
}

TEST(Periodic, AHandfulOfPointsInALargeBox)
{
  fd3::PeriodicBox box;
  for (int k = 0; k < 3; ++k)
    box.hi[k] = 10;
  for (std::size_t n : {1, 2, 3, 7})
  {
    const Points p = fd3test::scaled(fd3test::uniformCube(n, 9), 10);
    const auto t = checked(p, box);
    EXPECT_EQ(t.stats.insertedPoints, n);
    EXPECT_GT(t.numberOfTetrahedra(), 0u);
  }
}

TEST(Periodic, PlanesAcrossAWideGap)
{
  // Points on the planes z = 0, 0.1 (wrapped from 1.1) and 0.37: the first shell holds no image
  // below the lowest plane, which is then on the covering's hull, though its tetrahedra's spheres
  // are small. Its hull faces at the box's points ask for the images across the gap.
  const Points p = fd3test::generate("planes", 600, 3);
  const auto t = checked(p, fd3::PeriodicBox());
  EXPECT_EQ(t.stats.insertedPoints, 600u);
}

TEST(Periodic, ASlabAcrossAVacuum)
{
  // A material's slab under a vacuum, in a box periodic on every axis (surface simulations): the
  // tetrahedra across the vacuum join the slab's two surfaces. Their images are those near the
  // surfaces, not the slab's whole thickness about each hull face of the first covering: with
  // a period's box about each face, and boxes about the spheres, this set took 21.8 images a
  // point; with caps on the faces' outer sides and balls about the spheres, 4.6.
  Points p = fd3test::uniformCube(6000, 5);
  for (std::size_t i = 2; i < p.size(); i += 3)
    p[i] *= 0.3;
  const auto t = checked(p, fd3::PeriodicBox());
  EXPECT_EQ(t.stats.insertedPoints, 6000u);
  EXPECT_LT(t.imagePoints, 8 * 6000u);
}

TEST(Periodic, SlabsAndColumns)
{
  const Points p = fd3test::uniformCube(800, 6);
  for (const auto& axes :
    {std::array<bool, 3>{true, true, false}, std::array<bool, 3>{false, true, true},
      std::array<bool, 3>{true, false, false}, std::array<bool, 3>{false, false, true}})
  {
    fd3::PeriodicBox box;
    std::copy(axes.begin(), axes.end(), box.periodic);
    const auto t = checked(p, box);
    EXPECT_EQ(t.stats.insertedPoints, 800u);
  }
  // A slab's tetrahedra under its highest and lowest planes reach a period across; the images
  // they need are those of the few points in their thin caps, not a period's shell of them all.
  {
    const Points many = fd3test::uniformCube(6000, 18);
    fd3::PeriodicBox slab;
    slab.periodic[2] = false;
    const auto t = checked(many, slab);
    EXPECT_LT(t.imagePoints, 2 * 6000u);
  }
  // Points of a slab far from the box along its free axis: only the periodic axes wrap.
  fd3::PeriodicBox slab;
  slab.periodic[2] = false;
  Points high = p;
  for (std::size_t i = 2; i < high.size(); i += 3)
    high[i] = 100 + high[i];
  const auto t = checked(high, slab);
  EXPECT_EQ(t.wraps[2], 0);
}

TEST(Periodic, PointsOutsideTheBoxAreWrapped)
{
  const Points p = fd3test::uniformCube(500, 8);
  const auto inside = checked(p, fd3::PeriodicBox());
  Points moved = p;
  const double shifts[] = {1, -1, 3, -7, 1e6};
  for (std::size_t i = 0; i < 500; i += 7)
    moved[i] += shifts[i % 5]; // x only: 0.3 - 1 is exact, 0.3 - 7 wraps back to a rounding
  moved[3 * 10 + 1] = -0.1;    // wraps to 0.9 only as a sum of two doubles
  moved[3 * 11 + 2] = 1.0;     // the box's upper side: wraps to 0
  const auto t = checked(moved, fd3::PeriodicBox());
  EXPECT_EQ(t.wraps[0], -(shifts[0] < 0) + int(std::floor(moved[0])));
  EXPECT_EQ(t.wraps[3 * 10 + 1], -1);
  EXPECT_EQ(t.wraps[3 * 11 + 2], 1);
  // Points moved by whole periods (exactly) have the same tetrahedra.
  Points whole = p;
  for (std::size_t i = 0; i < 500; i += 3)
    whole[3 * i + 1] += (i % 2 ? 4 : -2); // exact where the sum is
  std::size_t exact = 0;
  for (std::size_t i = 0; i < 500; i += 3)
    exact += (whole[3 * i + 1] - (i % 2 ? 4 : -2)) == p[3 * i + 1];
  if (exact == (500 + 2) / 3)
    EXPECT_EQ(canonical(checked(whole, fd3::PeriodicBox())), canonical(inside));
}

TEST(Periodic, RepeatsAcrossTheBoxAreMerged)
{
  Points p = fd3test::uniformCube(300, 10);
  std::copy_n(std::array<double, 3>{0.75, 0.5, 0.25}.begin(), 3, p.begin());
  p.insert(p.end(), {1.75, 0.5, -1.75}); // point 0 again, one and two periods away (exact)
  p.insert(p.end(), {p[3], p[4], p[5]}); // point 1 again
  const auto t = checked(p, fd3::PeriodicBox());
  EXPECT_EQ(t.stats.duplicatesMerged, 2u);
  EXPECT_EQ(t.stats.insertedPoints, 300u);
  EXPECT_EQ(t.representative[300], 0u);
  EXPECT_EQ(t.representative[301], 1u);
}

// A point that differs from another by less than the box's doubles resolve once both are
// wrapped: its images would have the same records, so it is skipped, and said to be.
TEST(Periodic, PointsTooCloseForTheBoxAreSkipped)
{
  Points p = fd3test::uniformCube(300, 15);
  std::copy_n(std::array<double, 3>{0x1p-60, 0.5, 0.25}.begin(), 3, p.begin());
  p.insert(p.end(), {0x1p-61, 0.5, 0.25}); // its image at 1 + 2^-61 rounds as 1 + 2^-60 does
  const auto t = fd3::triangulatePeriodic(p.data(), 301, fd3::PeriodicBox());
  ASSERT_EQ(t.status, fd3::Status::Ok);
  EXPECT_EQ(t.stats.closePointsSkipped, 1u);
  EXPECT_EQ(t.representative[300], 0u);
  EXPECT_EQ(t.stats.insertedPoints, 300u);
  // Without the close one, the validator holds.
  p.resize(900);
  checked(p, fd3::PeriodicBox());
}

TEST(Periodic, BadInput)
{
  Points p = fd3test::uniformCube(200, 12);
  p[5] = std::numeric_limits<double>::quiet_NaN();
  p[9] = std::numeric_limits<double>::infinity();
  const auto t = checked(p, fd3::PeriodicBox());
  EXPECT_EQ(t.stats.nonFinitePoints, 2u);
  EXPECT_EQ(t.representative[1], fd3::kNoPoint);
  EXPECT_EQ(t.stats.insertedPoints, 198u);

  fd3::PeriodicBox none;
  std::fill(none.periodic, none.periodic + 3, false);
  EXPECT_THROW(fd3::triangulatePeriodic(p.data(), 200, none), std::invalid_argument);
  fd3::PeriodicBox inverted;
  inverted.hi[1] = -1;
  EXPECT_THROW(fd3::triangulatePeriodic(p.data(), 200, inverted), std::invalid_argument);
  fd3::PeriodicBox infinite;
  infinite.hi[2] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(fd3::triangulatePeriodic(p.data(), 200, infinite), std::invalid_argument);

  Points far = fd3test::uniformCube(50, 13);
  far[0] = 1e20; // 1e20 periods away
  EXPECT_EQ(
    fd3::triangulatePeriodic(far.data(), 50, fd3::PeriodicBox()).status, fd3::Status::OutOfRange);
  EXPECT_EQ(fd3::triangulatePeriodic(p.data(), 0, fd3::PeriodicBox()).status, fd3::Status::Empty);
  // Coplanar points in a slab whose free axis is across their plane: no tetrahedron.
  Points flat = fd3test::uniformCube(50, 14);
  for (std::size_t i = 2; i < flat.size(); i += 3)
    flat[i] = 0.5;
  fd3::PeriodicBox slab;
  slab.periodic[2] = false;
  EXPECT_EQ(fd3::triangulatePeriodic(flat.data(), 50, slab).status, fd3::Status::Degenerate);
}

/// Six times the volume of a placed tetrahedron.
double placedSixVolume(const fd3::PeriodicPlacement& placed, const Points& p, std::size_t t)
{
  const std::size_t count = p.size() / 3;
  const double* q[4];
  for (int i = 0; i < 4; ++i)
  {
    const std::uint32_t v = placed.tetrahedra[4 * t + i];
    q[i] = v < count ? &p[3 * v] : &placed.imagePoints[3 * (v - count)];
  }
  double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      e[i][k] = q[i + 1][k] - q[0][k];
  return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
    e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
    e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
}

// Placed as drawn, the periodic tetrahedra tile one period: positive, their volumes the box's,
// each image a whole number of periods from its input point (points outside the box included),
// one image per point and shift.
TEST(Periodic, PlacedTetrahedraTileOnePeriod)
{
  Points p = fd3test::uniformCube(2000, 21);
  for (std::size_t i = 0; i < 2000; i += 9)
    p[3 * i] += (i % 2 ? 3.0 : -2.0); // outside the box, by whole periods in x
  fd3::PeriodicBox box;
  std::fill(box.hi, box.hi + 3, 2.0);
  for (double& x : p)
    x *= 2;
  const auto t = checked(p, box);
  const fd3::PeriodicPlacement placed = fd3::placePeriodic(p.data(), 2000, t, box);
  ASSERT_EQ(placed.tetrahedra.size(), t.tetrahedra.size());
  ASSERT_EQ(placed.imagePoints.size(), 3 * placed.numberOfImages());
  ASSERT_EQ(placed.imageShifts.size(), 3 * placed.numberOfImages());
  double volume = 0;
  for (std::size_t c = 0; c < t.numberOfTetrahedra(); ++c)
  {
    const double six = placedSixVolume(placed, p, c);
    EXPECT_GT(six, 0);
    volume += six / 6;
  }
  EXPECT_NEAR(volume, 8.0, 8.0 * 1e-12);
  std::set<std::array<std::int64_t, 4>> distinct;
  for (std::size_t k = 0; k < placed.numberOfImages(); ++k)
  {
    const std::uint32_t source = placed.imageSources[k];
    bool moved = false;
    for (int a = 0; a < 3; ++a)
    {
      const std::int32_t shift = placed.imageShifts[3 * k + a];
      moved = moved || shift != 0;
      EXPECT_EQ(placed.imagePoints[3 * k + a], p[3 * source + a] + 2.0 * shift);
    }
    EXPECT_TRUE(moved);
    distinct.insert({source, placed.imageShifts[3 * k], placed.imageShifts[3 * k + 1],
      placed.imageShifts[3 * k + 2]});
  }
  EXPECT_EQ(distinct.size(), placed.numberOfImages());
  // An input point outside the box is drawn only as its images.
  const auto used = std::count(placed.tetrahedra.begin(), placed.tetrahedra.end(), 0u);
  EXPECT_EQ(used, 0);
}

// The periodic DTFE has no boundary: its field integrates over the box to the number of points,
// whatever the points' distance to the box's sides.
TEST(Periodic, DensityHasNoBoundaryEffect)
{
  const Points p = fd3test::uniformCube(3000, 22);
  const auto t = checked(p, fd3::PeriodicBox());
  const auto placed = fd3::placePeriodic(p.data(), 3000, t, fd3::PeriodicBox());
  const std::vector<double> density = fd3::densities(p.data(), 3000, t, placed);
  double integral = 0;
  for (std::size_t c = 0; c < t.numberOfTetrahedra(); ++c)
  {
    double mean = 0;
    for (int i = 0; i < 4; ++i)
      mean += density[t.tetrahedra[4 * c + i]] / 4;
    integral += mean * placedSixVolume(placed, p, c) / 6;
  }
  EXPECT_NEAR(integral, 3000.0, 3000.0 * 1e-12);
  // Points by the box's sides have whole stars: their mean volume per point, 1 / density, is the
  // others' (without the repeats, the hull's points would have part of a star).
  const Points many = fd3test::uniformCube(20000, 23);
  const auto m = fd3::triangulatePeriodic(many.data(), 20000, fd3::PeriodicBox());
  const std::vector<double> rho =
    fd3::densities(many.data(), 20000, m, fd3::placePeriodic(many.data(), 20000, m, {}));
  double mean[2] = {0, 0};
  std::size_t n[2] = {0, 0};
  for (std::size_t i = 0; i < 20000; ++i)
  {
    double side = 1;
    for (int a = 0; a < 3; ++a)
      side = std::min({side, many[3 * i + a], 1 - many[3 * i + a]});
    mean[side < 0.02] += 1 / rho[i];
    ++n[side < 0.02];
  }
  EXPECT_NEAR(mean[1] / n[1], mean[0] / n[0], 0.05 * mean[0] / n[0]);

  Points lattice;
  for (int i = 0; i < 1000; ++i)
    lattice.insert(lattice.end(), {0.1 * (i % 10), 0.1 * (i / 10 % 10), 0.1 * (i / 100)});
  const auto l = checked(lattice, fd3::PeriodicBox());
  const auto lrho =
    fd3::densities(lattice.data(), 1000, l, fd3::placePeriodic(lattice.data(), 1000, l, {}));
  // The stars fill the box four times over, where a boundary would leave them short.
  double cells = 0;
  for (const double value : lrho)
    cells += 1 / value;
  EXPECT_NEAR(cells, 1.0, 1e-12);
}

/// A periodic simplex: its vertices as (input point, shift from the least vertex), sorted.
using PeriodicSimplex = std::vector<std::array<std::int64_t, 4>>;

PeriodicSimplex periodicSimplex(std::vector<std::array<std::int64_t, 4>> vertices)
{
  const auto least = *std::min_element(vertices.begin(), vertices.end());
  for (auto& v : vertices)
    for (int a = 1; a < 4; ++a)
      v[a] -= least[a];
  std::sort(vertices.begin(), vertices.end());
  return vertices;
}

/// The simplices of an alpha complex, `size` point ids each, as periodic simplices, where
/// vertex(id) gives an id's input point and shift.
template <typename Vertex>
std::set<PeriodicSimplex> periodicSimplices(
  const std::vector<std::uint32_t>& ids, int size, Vertex vertex)
{
  std::set<PeriodicSimplex> simplices;
  for (std::size_t s = 0; s < ids.size(); s += size)
  {
    std::vector<std::array<std::int64_t, 4>> vertices;
    for (int k = 0; k < size; ++k)
      vertices.push_back(vertex(ids[s + k]));
    EXPECT_TRUE(simplices.insert(periodicSimplex(vertices)).second) << "listed twice";
  }
  return simplices;
}

// The periodic alpha complex is the ordinary one of the points repeated 3 x 3 x 3 times, around
// the middle copy: the same tetrahedra, triangles, lines and lone vertices, each periodic simplex
// once. Weighted (`weights` not empty), the weighted complexes, every copy with its point's weight.
void expectAlphaComplexOfRepeatedPoints(const Points& p, const std::vector<double>& weights)
{
  const std::size_t n = p.size() / 3;
  const double* w = weights.empty() ? nullptr : weights.data();
  const auto t = fd3::triangulatePeriodic(p.data(), w, n, fd3::PeriodicBox());
  ASSERT_EQ(t.status, fd3::Status::Ok);
  const auto placed = fd3::placePeriodic(p.data(), n, t, fd3::PeriodicBox());
  const auto placedVertex = [&](std::uint32_t id) -> std::array<std::int64_t, 4> {
    if (id < n)
      return {id, 0, 0, 0};
    const std::int32_t* s = &placed.imageShifts[3 * (id - n)];
    return {placed.imageSources[id - n], s[0], s[1], s[2]};
  };
  Points repeated;
  std::vector<double> repeatedWeights;
  for (int copy = 0; copy < 27; ++copy)
    for (std::size_t i = 0; i < n; ++i)
    {
      for (int a = 0; a < 3; ++a)
        repeated.push_back(p[3 * i + a] + (copy / (a == 0 ? 1 : a == 1 ? 3 : 9) % 3 - 1));
      if (w)
        repeatedWeights.push_back(w[i]);
    }
  const double* rw = w ? repeatedWeights.data() : nullptr;
  const auto repeatedVertex = [&](std::uint32_t id) -> std::array<std::int64_t, 4> {
    const int copy = int(id / n);
    return {std::int64_t(id % n), copy % 3 - 1, copy / 3 % 3 - 1, copy / 9 - 1};
  };
  fd3::Options options;
  options.computeNeighbors = true;
  const fd3::Triangulation whole = w ? fd3::triangulate(repeated.data(), rw, 27 * n, options)
                                     : fd3::triangulate(repeated.data(), 27 * n, options);
  const std::uint32_t middle = 13; // the copy with no shift
  for (const double alpha : {0.05, 0.08, 0.12})
  {
    const fd3::AlphaComplex periodic =
      fd3::alphaComplex(p.data(), w, n, placed, t.hidden, alpha, 3);
    const fd3::AlphaComplex reference =
      fd3::alphaComplex(repeated.data(), rw, 27 * n, whole, alpha, 3);
    // The reference's simplices with a vertex in the middle copy, each periodic one once.
    const auto inMiddle = [&](const std::vector<std::uint32_t>& ids, int size) {
      std::vector<std::uint32_t> chosen;
      std::set<PeriodicSimplex> seen;
      for (std::size_t s = 0; s < ids.size(); s += size)
      {
        bool middleVertex = false;
        std::vector<std::array<std::int64_t, 4>> vertices;
        for (int k = 0; k < size; ++k)
        {
          middleVertex = middleVertex || ids[s + k] / n == middle;
          vertices.push_back(repeatedVertex(ids[s + k]));
        }
        if (middleVertex && seen.insert(periodicSimplex(vertices)).second)
          chosen.insert(chosen.end(), &ids[s], &ids[s] + size);
      }
      return chosen;
    };
    std::vector<std::uint32_t> periodicTets, referenceTets;
    for (const std::uint32_t c : periodic.tetrahedra)
      periodicTets.insert(
        periodicTets.end(), &placed.tetrahedra[4 * c], &placed.tetrahedra[4 * c] + 4);
    for (const std::uint32_t c : reference.tetrahedra)
      referenceTets.insert(
        referenceTets.end(), &whole.tetrahedra[4 * c], &whole.tetrahedra[4 * c] + 4);
    EXPECT_EQ(periodicSimplices(periodicTets, 4, placedVertex),
      periodicSimplices(inMiddle(referenceTets, 4), 4, repeatedVertex));
    EXPECT_EQ(periodicSimplices(periodic.triangles, 3, placedVertex),
      periodicSimplices(inMiddle(reference.triangles, 3), 3, repeatedVertex));
    EXPECT_EQ(periodicSimplices(periodic.lines, 2, placedVertex),
      periodicSimplices(inMiddle(reference.lines, 2), 2, repeatedVertex));
    std::vector<std::uint32_t> lone;
    for (const std::uint32_t v : reference.vertices)
      if (v / n == middle)
        lone.push_back(v % n);
    EXPECT_EQ(periodic.vertices, lone);
    EXPECT_FALSE(
      periodic.triangles.empty() || periodic.lines.empty() || periodic.tetrahedra.empty());
  }
}

TEST(Periodic, AlphaComplexIsTheRepeatedPointsOne)
{
  expectAlphaComplexOfRepeatedPoints(fd3test::uniformCube(400, 24), {});
}

// With radii up to 0.06, some points hidden: hidden points are in none of it, and a simplex's
// radius is its smallest orthogonal sphere's, its images' weights their points'.
TEST(Periodic, WeightedAlphaComplexIsTheRepeatedPointsOne)
{
  const Points p = fd3test::uniformCube(400, 25);
  std::vector<double> w(400);
  for (std::size_t i = 0; i < w.size(); ++i)
    w[i] = std::pow(0.06 * double((i * 7919) % 400) / 400, 2);
  expectAlphaComplexOfRepeatedPoints(p, w);
  EXPECT_FALSE(
    fd3::triangulatePeriodic(p.data(), w.data(), 400, fd3::PeriodicBox()).hidden.empty());
}

// One point in the box: every tetrahedron holds four images of it, and each edge is met as
// several translates; the complex lists each once: the three axes' edges, of half-length 0.5.
TEST(Periodic, AlphaComplexOfOnePoint)
{
  const Points p = {0.25, 0.5, 0.75};
  const auto t = checked(p, fd3::PeriodicBox());
  const auto placed = fd3::placePeriodic(p.data(), 1, t, fd3::PeriodicBox());
  const fd3::AlphaComplex shape = fd3::alphaComplex(p.data(), 1, placed, 0.6);
  EXPECT_TRUE(shape.tetrahedra.empty());
  EXPECT_TRUE(shape.triangles.empty());
  EXPECT_TRUE(shape.vertices.empty());
  ASSERT_EQ(shape.lines.size(), 6u);
  const auto point = [&](std::uint32_t id) {
    return id < 1 ? &p[0] : &placed.imagePoints[3 * (id - 1)];
  };
  std::set<int> axes;
  for (std::size_t l = 0; l < 6; l += 2)
  {
    const double* a = point(shape.lines[l]);
    const double* b = point(shape.lines[l + 1]);
    int axis = -1;
    for (int k = 0; k < 3; ++k)
      if (std::fabs(a[k] - b[k]) == 1.0)
        axis = k;
      else
        EXPECT_EQ(a[k], b[k]);
    axes.insert(axis);
  }
  EXPECT_EQ(axes, (std::set<int>{0, 1, 2}));
  // A larger alpha keeps every tetrahedron: six of the cube's, a unit of volume.
  EXPECT_EQ(fd3::alphaComplex(p.data(), 1, placed, 10).tetrahedra.size(), t.numberOfTetrahedra());
}

/// Each face's neighbour has a face back to the cell (as many faces each way: a point's own
/// images make faces to itself).
void expectSymmetricNeighbours(const fd3::VoronoiCells& cells)
{
  std::vector<std::size_t> cellOf(
    *std::max_element(cells.generators.begin(), cells.generators.end()) + 1);
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
    cellOf[cells.generators[c]] = c;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> faces;
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
    for (std::size_t f = cells.cellFaces[c]; f < cells.cellFaces[c + 1]; ++f)
      if (cells.faceNeighbors[f] < fd3::kBoxFace)
        ++faces[{cells.generators[c], cells.faceNeighbors[f]}];
  for (const auto& [pair, n] : faces)
  {
    const auto back = faces.find({pair.second, pair.first});
    ASSERT_NE(back, faces.end());
    EXPECT_EQ(back->second, n);
  }
}

TEST(PeriodicVoronoi, CellsFillTheBox)
{
  const Points p = fd3test::uniformCube(3000, 16);
  const fd3::VoronoiCells cells = fd3::voronoiCellsPeriodic(p.data(), 3000, fd3::PeriodicBox());
  ASSERT_EQ(cells.status, fd3::Status::Ok);
  ASSERT_EQ(cells.numberOfCells(), 3000u);
  EXPECT_NEAR(sum(cells.volumes), 1.0, 1e-12);
  expectSymmetricNeighbours(cells);
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
    EXPECT_EQ(cells.numberOfNeighbors(c), cells.numberOfFaces(c)); // no face on the box
  // The cells' polyhedra hold their generators' places.
  const std::vector<std::size_t> none;
  for (std::size_t c = 0; c < 20; ++c)
  {
    double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
    for (std::size_t i = cells.cellPointStart[c]; i < cells.cellPointStart[c + 1]; ++i)
      for (int k = 0; k < 3; ++k)
      {
        lo[k] = std::min(lo[k], cells.points[3 * cells.cellPoints[i] + k]);
        hi[k] = std::max(hi[k], cells.points[3 * cells.cellPoints[i] + k]);
      }
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_LE(lo[k], p[3 * cells.generators[c] + k]);
      EXPECT_GE(hi[k], p[3 * cells.generators[c] + k]);
    }
  }
}

// The lattice's ties, broken alike in every copy: the cells are cubes (with faces of no area
// where the perturbation splits a vertex of eight cells), and each point's density, from its
// whole star, sums as the box's: the sum of 1/density is the stars' volumes over 4, the box's.
TEST(PeriodicVoronoi, LatticeCellsAreEqualCubes)
{
  const Points p = cubicLattice(10, 0.1);
  fd3::VoronoiOptions options;
  options.density = true;
  const fd3::VoronoiCells cells =
    fd3::voronoiCellsPeriodic(p.data(), 1000, fd3::PeriodicBox(), options);
  ASSERT_EQ(cells.status, fd3::Status::Ok);
  ASSERT_EQ(cells.numberOfCells(), 1000u);
  double inverseDensities = 0;
  for (std::size_t c = 0; c < 1000; ++c)
  {
    EXPECT_NEAR(cells.volumes[c], 1e-3, 1e-15) << c;
    EXPECT_GE(cells.numberOfNeighbors(c), 6u) << c;
    inverseDensities += 1 / cells.densities[c];
  }
  EXPECT_NEAR(sum(cells.volumes), 1.0, 1e-12);
  EXPECT_NEAR(inverseDensities, 1.0, 1e-12);
  expectSymmetricNeighbours(cells);
}

TEST(PeriodicVoronoi, OnePointFillsTheBox)
{
  fd3::PeriodicBox box;
  std::fill(box.hi, box.hi + 3, 10.0);
  const Points p = {2.5, 7.0, 1.0};
  const fd3::VoronoiCells cells = fd3::voronoiCellsPeriodic(p.data(), 1, box);
  ASSERT_EQ(cells.status, fd3::Status::Ok);
  ASSERT_EQ(cells.numberOfCells(), 1u);
  EXPECT_NEAR(cells.volumes[0], 1000.0, 1e-9);
  // Itself, across each side (and across the edges and corners that the perturbation's split
  // of the cube's vertices makes faces of no area).
  EXPECT_GE(cells.numberOfNeighbors(0), 6u);
  for (const std::uint32_t n : cells.faceNeighbors)
    EXPECT_EQ(n, 0u);
}

#ifdef FD3_TEST_WITH_VOROPP
// Against Voro++'s container with the same axes periodic (a non-periodic axis is clipped to the
// box by both), to 1e-9 of each volume.
TEST(PeriodicVoronoi, SameVolumesAsVoropp)
{
  const Points p = fd3test::uniformCube(4000, 17);
  for (const auto& axes : {std::array<bool, 3>{true, true, true},
         std::array<bool, 3>{true, true, false}, std::array<bool, 3>{false, true, false}})
  {
    fd3::PeriodicBox box;
    std::copy(axes.begin(), axes.end(), box.periodic);
    const fd3::VoronoiCells cells = fd3::voronoiCellsPeriodic(p.data(), 4000, box);
    ASSERT_EQ(cells.status, fd3::Status::Ok);
    ASSERT_EQ(cells.numberOfCells(), 4000u);
    const int blocks = fd3test::voroppBlocks(4000);
    voro::container container(
      0, 1, 0, 1, 0, 1, blocks, blocks, blocks, axes[0], axes[1], axes[2], 8);
    for (std::size_t i = 0; i < 4000; ++i)
      container.put(int(i), p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    const std::vector<double> expected = fd3test::voroppVolumes(container, 4000);
    for (std::size_t c = 0; c < 4000; ++c)
    {
      const double reference = expected[cells.generators[c]];
      EXPECT_NEAR(cells.volumes[c], reference, 1e-9 * reference) << cells.generators[c];
    }
    EXPECT_NEAR(sum(cells.volumes), 1.0, 1e-12);
    expectSymmetricNeighbours(cells);
  }
}
#endif

} // namespace
