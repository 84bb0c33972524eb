// The periodic tetrahedralization (fd3/Periodic.h), decided by the exact periodic validator:
// uniform points, lattices commensurate with the box (ties across its faces, with images that no
// double holds), a handful of points in a large box, slabs and columns, points outside the box,
// repeats, any thread count, and bad input.
#include "PeriodicValidator.h"
#include "PointSets.h"
#include "fd3/Periodic.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <vector>

namespace
{
using fd3test::Points;

fd3test::PeriodicDomain domainOf(const fd3::PeriodicBox& box)
{
  fd3test::PeriodicDomain domain;
  for (int k = 0; k < 3; ++k)
  {
    domain.lo[k] = box.lo[k];
    domain.hi[k] = box.hi[k];
    domain.periodic[k] = box.periodic[k];
  }
  return domain;
}

std::vector<fd3test::PeriodicTetrahedron> tetrahedraOf(const fd3::PeriodicTriangulation& t)
{
  std::vector<fd3test::PeriodicTetrahedron> out(t.numberOfTetrahedra());
  for (std::size_t c = 0; c < out.size(); ++c)
    for (int i = 0; i < 4; ++i)
    {
      out[c].ids[i] = t.tetrahedra[4 * c + i];
      for (int k = 0; k < 3; ++k)
        out[c].offsets[i][k] = t.offsets[12 * c + 3 * i + k];
    }
  return out;
}

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

/// The tetrahedra as sets of (id, offset) up to a translation, for comparing two runs.
std::set<std::array<std::array<int, 4>, 4>> canonical(const fd3::PeriodicTriangulation& t)
{
  std::set<std::array<std::array<int, 4>, 4>> out;
  for (std::size_t c = 0; c < t.numberOfTetrahedra(); ++c)
  {
    std::array<std::array<int, 4>, 4> v;
    for (int i = 0; i < 4; ++i)
      v[i] = {int(t.tetrahedra[4 * c + i]), t.offsets[12 * c + 3 * i],
        t.offsets[12 * c + 3 * i + 1], t.offsets[12 * c + 3 * i + 2]};
    std::sort(v.begin(), v.end());
    out.insert(v);
  }
  return out;
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

} // namespace
