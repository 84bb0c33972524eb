// The alpha complex on several threads against the definition, computed here one simplex at a time
// with a set of covered edges (vtkDelaunay3D's rule: tetrahedra of circumradius <= alpha, then the
// faces, then the edges of the others that no kept simplex covers, then the points on none): the
// same simplices in the same order, on uniform, clustered, lattice (exact ties) and torus points,
// at alphas from a few edges' length to the whole set's.
#include "PointSets.h"
#include "fd3/Delaunay.h"
#include "fd3/Measures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <unordered_set>

namespace
{
std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b)
{
  return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
}

fd3::AlphaComplex definition(const fd3test::Points& xyz, const fd3::Triangulation& r, double alpha)
{
  constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const double alpha2 = alpha * alpha;
  auto p = [&](std::uint32_t id) { return xyz.data() + 3 * std::size_t(id); };
  const std::uint32_t* tv = r.tetrahedra.data();
  const std::size_t tets = r.numberOfTetrahedra();
  fd3::AlphaComplex complex;
  std::vector<bool> kept(tets), used(xyz.size() / 3);
  std::unordered_set<std::uint64_t> covered;
  auto cover = [&](const std::uint32_t* ids, int n) {
    for (int i = 0; i < n; ++i)
    {
      used[ids[i]] = true;
      for (int j = i + 1; j < n; ++j)
        covered.insert(edgeKey(ids[i], ids[j]));
    }
  };
  for (std::size_t t = 0; t < tets; ++t)
    if (fd3::tetrahedronCircumradius2(
          p(tv[4 * t]), p(tv[4 * t + 1]), p(tv[4 * t + 2]), p(tv[4 * t + 3])) <= alpha2)
    {
      kept[t] = true;
      complex.tetrahedra.push_back(static_cast<std::uint32_t>(t));
      cover(tv + 4 * t, 4);
    }
  // Each face in its outward order, as the kernel lists them (TetMesh.h, kFaceVertices).
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (std::size_t t = 0; t < tets; ++t)
    for (int f = 0; f < 4 && !kept[t]; ++f)
    {
      const std::uint32_t across = r.neighbors[4 * t + f];
      if (across != fd3::kNoNeighbor && (kept[across >> 2] || (across >> 2) < t))
        continue;
      const std::uint32_t face[3] = {
        tv[4 * t + kFace[f][0]], tv[4 * t + kFace[f][1]], tv[4 * t + kFace[f][2]]};
      if (fd3::triangleCircumradius2(p(face[0]), p(face[1]), p(face[2])) <= alpha2)
      {
        complex.triangles.insert(complex.triangles.end(), face, face + 3);
        cover(face, 3);
      }
    }
  for (std::size_t t = 0; t < tets; ++t)
    for (int e = 0; e < 6 && !kept[t]; ++e)
    {
      const std::uint32_t edge[2] = {tv[4 * t + kEdges[e][0]], tv[4 * t + kEdges[e][1]]};
      if (!covered.count(edgeKey(edge[0], edge[1])) &&
        fd3::distance2(p(edge[0]), p(edge[1])) * 0.25 <= alpha2)
      {
        complex.lines.insert(complex.lines.end(), edge, edge + 2);
        cover(edge, 2);
      }
    }
  for (std::uint32_t i = 0; i < used.size(); ++i)
    if (!used[i] && fd3::isFinite(p(i)))
      complex.vertices.push_back(i);
  return complex;
}

TEST(AlphaComplex, SameSimplicesAsTheDefinitionOnEveryThreadCount)
{
  for (const char* kind : {"cube", "clusters", "lattice", "torus"})
  {
    SCOPED_TRACE(kind);
    const fd3test::Points p = fd3test::generate(kind, 20000, 3);
    const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3);
    ASSERT_EQ(r.status, fd3::Status::Ok);
    double lo[3] = {p[0], p[1], p[2]}, hi[3] = {p[0], p[1], p[2]};
    for (std::size_t i = 0; i < p.size(); ++i)
    {
      lo[i % 3] = std::min(lo[i % 3], p[i]);
      hi[i % 3] = std::max(hi[i % 3], p[i]);
    }
    const double spacing =
      std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / std::cbrt(double(p.size() / 3));
    for (const double factor : {0.2, 0.5, 0.8, 1.5, 1000.0})
    {
      SCOPED_TRACE(factor);
      const fd3::AlphaComplex expected = definition(p, r, factor * spacing);
      for (const int threads : {1, 4})
      {
        const fd3::AlphaComplex got =
          fd3::alphaComplex(p.data(), p.size() / 3, r, factor * spacing, threads);
        EXPECT_TRUE(got.tetrahedra == expected.tetrahedra) << threads << " threads";
        EXPECT_EQ(got.triangles, expected.triangles) << threads << " threads";
        EXPECT_EQ(got.lines, expected.lines) << threads << " threads";
        EXPECT_EQ(got.vertices, expected.vertices) << threads << " threads";
      }
    }
  }
}

} // namespace
