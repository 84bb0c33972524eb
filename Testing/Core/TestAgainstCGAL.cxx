// The weighted tetrahedralization against CGAL's Regular_triangulation_3 (a test-only peer): on
// generic input, where the regular tetrahedralization is unique, the same vertices and the same
// tetrahedra, whatever the ties' perturbation.
#include "ExactValidator.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
using fd3test::Points;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel,
  CGAL::Regular_triangulation_vertex_base_3<Kernel>>;
using CellBase = CGAL::Regular_triangulation_cell_base_3<Kernel>;
using Regular =
  CGAL::Regular_triangulation_3<Kernel, CGAL::Triangulation_data_structure_3<VertexBase, CellBase>>;
using Tetrahedra = std::vector<std::array<std::uint32_t, 4>>;

/// CGAL's tetrahedra (sorted ids, sorted) and its vertices' ids (sorted).
void cgalRegular(const Points& p, const std::vector<double>& w, Tetrahedra& tetrahedra,
  std::vector<std::uint32_t>& vertices)
{
  std::vector<std::pair<Regular::Weighted_point, std::uint32_t>> input;
  for (std::size_t i = 0; i < w.size(); ++i)
    input.emplace_back(
      Regular::Weighted_point(Kernel::Point_3(p[3 * i], p[3 * i + 1], p[3 * i + 2]), w[i]),
      static_cast<std::uint32_t>(i));
  const Regular regular(input.begin(), input.end());
  for (auto c = regular.finite_cells_begin(); c != regular.finite_cells_end(); ++c)
  {
    std::array<std::uint32_t, 4> ids;
    for (int k = 0; k < 4; ++k)
      ids[k] = c->vertex(k)->info();
    std::sort(ids.begin(), ids.end());
    tetrahedra.push_back(ids);
  }
  std::sort(tetrahedra.begin(), tetrahedra.end());
  for (auto v = regular.finite_vertices_begin(); v != regular.finite_vertices_end(); ++v)
    vertices.push_back(v->info());
  std::sort(vertices.begin(), vertices.end());
}

/// Returns how many points are hidden.
std::size_t expectSameAsCGAL(const Points& p, const std::vector<double>& w, const std::string& what)
{
  const std::size_t n = w.size();
  const fd3::Triangulation ours = fd3::triangulate(p.data(), w.data(), n);
  EXPECT_EQ(ours.status, fd3::Status::Ok) << what;
  Tetrahedra theirs;
  std::vector<std::uint32_t> theirVertices;
  cgalRegular(p, w, theirs, theirVertices);
  std::vector<std::uint32_t> ourVertices;
  for (std::uint32_t i = 0; i < n; ++i)
    if (!std::binary_search(ours.hidden.begin(), ours.hidden.end(), i))
      ourVertices.push_back(i);
  EXPECT_EQ(ourVertices, theirVertices) << what;
  EXPECT_EQ(ours.hidden.size(), n - theirVertices.size()) << what;
  EXPECT_TRUE(fd3test::canonicalTetrahedra(ours.tetrahedra) == theirs)
    << what << ": " << ours.numberOfTetrahedra() << " tetrahedra against CGAL's " << theirs.size();
  return ours.hidden.size();
}

std::vector<double> squaredRadii(std::size_t n, double lo, double hi, std::uint64_t seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> radius(lo, hi);
  std::vector<double> w(n);
  for (double& x : w)
    x = std::pow(radius(random), 2);
  return w;
}

TEST(AgainstCGAL, UniformPointsWithRandomRadii)
{
  for (const double largest : {0.01, 0.05})
    expectSameAsCGAL(fd3test::uniformCube(20000, 3), squaredRadii(20000, 0.001, largest, 4),
      "radii up to " + std::to_string(largest));
}

TEST(AgainstCGAL, PackingWithAQuarterHidden)
{
  const std::size_t large = 6000, small = 2000;
  Points p = fd3test::uniformCube(large, 5);
  std::vector<double> w = squaredRadii(large, 0.06, 0.09, 6);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> offset(-0.004, 0.004);
  std::uniform_int_distribution<std::size_t> pick(0, large - 1);
  for (std::size_t i = 0; i < small; ++i)
  {
    const std::size_t c = pick(random);
    for (int k = 0; k < 3; ++k)
      p.push_back(p[3 * c + k] + offset(random));
    w.push_back(std::pow(0.001 * (1 + offset(random)), 2));
  }
  EXPECT_GE(expectSameAsCGAL(p, w, "packing"), small * 9 / 10);
}

TEST(AgainstCGAL, MoleculeWithVanDerWaalsRadii)
{
  std::vector<double> radii;
  const Points p = fd3test::molecule(3000, 8, radii);
  std::vector<double> w(radii.size());
  for (std::size_t i = 0; i < w.size(); ++i)
    w[i] = (radii[i] + 1.4) * (radii[i] + 1.4); // a water probe's surface
  expectSameAsCGAL(p, w, "molecule");
}
} // namespace
