// The Delaunay tessellation field estimate: its linear field integrates over the hull to the
// number of finite points (each tetrahedron's volume times the mean of its vertices' values);
// merged points carry their vertex's value, points on no tetrahedron NaN; on uniform points it
// is near (a little above) the points per volume.
#include "CoreTestUtilities.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"
#include "fd3/Measures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace
{
/// The integral over the hull of the field through the vertices' values.
double integral(const std::vector<double>& xyz, const fd3::Triangulation& mesh,
  const std::vector<double>& density)
{
  double total = 0;
  for (std::size_t t = 0; t < mesh.numberOfTetrahedra(); ++t)
  {
    const std::uint32_t* v = &mesh.tetrahedra[4 * t];
    const double volume =
      std::fabs(fd3::sixVolume(&xyz[3 * v[0]], &xyz[3 * v[1]], &xyz[3 * v[2]], &xyz[3 * v[3]])) / 6;
    total += volume * (density[v[0]] + density[v[1]] + density[v[2]] + density[v[3]]) / 4;
  }
  return total;
}

class DensitySets : public ::testing::TestWithParam<const char*>
{};

TEST_P(DensitySets, FieldIntegratesToThePoints)
{
  fd3test::Points xyz = fd3test::generate(GetParam(), 5000, 4);
  xyz.insert(xyz.end(), {xyz[3], xyz[4], xyz[5], xyz[3], xyz[4], xyz[5], NAN, 0, 0});
  const std::size_t n = xyz.size() / 3;
  const fd3::Triangulation mesh = fd3::triangulate(xyz.data(), n);
  ASSERT_EQ(mesh.status, fd3::Status::Ok);
  const std::vector<double> density = fd3::densities(xyz.data(), n, mesh);
  ASSERT_EQ(density.size(), n);
  EXPECT_NEAR(integral(xyz, mesh, density), double(n - 1), 1e-9 * double(n));
  EXPECT_EQ(density[n - 3], density[1]); // exact duplicates
  EXPECT_EQ(density[n - 2], density[1]);
  EXPECT_TRUE(std::isnan(density[n - 1]));
  for (std::size_t i = 0; i + 1 < n; ++i)
    EXPECT_GT(density[i], 0) << "point " << i;
}

INSTANTIATE_TEST_SUITE_P(
  Density, DensitySets, ::testing::Values("cube", "clusters", "lattice", "sphere", "torus"));

TEST(Density, UniformPointsNearTheirCount)
{
  const fd3test::Points xyz = fd3test::generate("cube", 20000, 8);
  const std::size_t n = xyz.size() / 3;
  const fd3::Triangulation mesh = fd3::triangulate(xyz.data(), n);
  std::vector<double> density = fd3::densities(xyz.data(), n, mesh);
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], xyz[3 * i + a]);
      hi[a] = std::max(hi[a], xyz[3 * i + a]);
    }
  const double expected = double(n) / ((hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]));
  // A star's volume varies, and 4 over it runs above the count per volume: the median by about
  // an eighth on uniform points. A missing factor (4, or 6 for the volume) would be far off.
  std::nth_element(density.begin(), density.begin() + n / 2, density.end());
  EXPECT_GT(density[n / 2], expected);
  EXPECT_LT(density[n / 2], 1.25 * expected);
}

// A cluster 1e-150 wide among unit points: its tetrahedra's volumes (near 1e-450) hold in no
// double, its inner points' density (near 1e450) is infinite, its hull points' finite (their stars
// reach the unit points); each value is the same whatever the points' order; the masses over the
// densities still sum to the hull's volume.
TEST(Density, AnyMagnitudeAndAnyOrder)
{
  // Unit points about 0, and the cluster at 0: beside 0.5 it would be one point.
  fd3test::Points xyz = fd3test::generate("cube", 2000, 3);
  for (double& x : xyz)
    x -= 0.5;
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int i = 0; i < 200; ++i)
    for (int a = 0; a < 3; ++a)
      xyz.push_back(1e-150 * unit(random));
  const std::size_t n = xyz.size() / 3;
  const fd3::Triangulation mesh = fd3::triangulate(xyz.data(), n);
  ASSERT_EQ(mesh.status, fd3::Status::Ok);
  const std::vector<double> density = fd3::densities(xyz.data(), n, mesh);
  std::size_t infinite = 0;
  double inverse = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    ASSERT_GT(density[i], 0) << "point " << i;
    infinite += std::isinf(density[i]);
    inverse += 1 / density[i];
    if (i < 2000)
      EXPECT_LT(density[i], 1e6) << "point " << i;
  }
  EXPECT_GT(infinite, 50u);
  double hull = 0;
  for (std::size_t t = 0; t < mesh.numberOfTetrahedra(); ++t)
  {
    const std::uint32_t* v = &mesh.tetrahedra[4 * t];
    hull +=
      std::fabs(fd3::sixVolume(&xyz[3 * v[0]], &xyz[3 * v[1]], &xyz[3 * v[2]], &xyz[3 * v[3]])) / 6;
  }
  EXPECT_NEAR(inverse, hull, 1e-9 * hull);

  // The points reversed: each point keeps its value, bit for bit.
  fd3test::Points reversed;
  for (std::size_t i = n; i-- > 0;)
    reversed.insert(reversed.end(), &xyz[3 * i], &xyz[3 * i + 3]);
  const fd3::Triangulation again = fd3::triangulate(reversed.data(), n);
  const std::vector<double> same = fd3::densities(reversed.data(), n, again);
  for (std::size_t i = 0; i < n; ++i)
    EXPECT_EQ(same[n - 1 - i], density[i]) << "point " << i;
}

TEST(Density, NoTetrahedraNoValues)
{
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const fd3::Triangulation mesh = fd3::triangulate(xyz.data(), 3);
  const std::vector<double> density = fd3::densities(xyz.data(), 3, mesh);
  ASSERT_EQ(density.size(), 3u);
  for (const double d : density)
    EXPECT_TRUE(std::isnan(d));
}
} // namespace
