// Alpha shapes as vtkDelaunay3D defines them, over an exact Delaunay tetrahedralization: kept
// tetrahedra first, then the lower-dimensional simplices that no kept simplex already covers.
// Unlike vtkDelaunay3D, whose bounding octahedron makes the hull faces it reports depend on cell
// numbering, every hull face is a candidate triangle here: the hull is exact.
#include "TetMesh.h"
#include "fd3/Delaunay.h"
#include "fd3/Measures.h"

#include <cmath>
#include <unordered_set>

namespace fd3
{
namespace
{
std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b)
{
  return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
}

constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
} // namespace

AlphaComplex alphaComplex(
  const double* xyz, std::size_t count, const Triangulation& triangulation, double alpha)
{
  AlphaComplex complex;
  const double alpha2 = alpha * alpha;
  const std::size_t tets = triangulation.numberOfTetrahedra();
  const std::uint32_t* tv = triangulation.tetrahedra.data();
  auto p = [&](std::uint32_t id) { return xyz + 3 * std::size_t(id); };

  std::vector<bool> kept(tets), used(count);
  std::unordered_set<std::uint64_t> coveredEdges;
  auto cover = [&](const std::uint32_t* ids, int n) {
    for (int i = 0; i < n; ++i)
      used[ids[i]] = true;
    for (int i = 0; i < n && n > 1; ++i)
      coveredEdges.insert(edgeKey(ids[i], ids[(i + 1) % n]));
  };

  for (std::size_t t = 0; t < tets; ++t)
  {
    const std::uint32_t* v = tv + 4 * t;
    if (tetrahedronCircumradius2(p(v[0]), p(v[1]), p(v[2]), p(v[3])) > alpha2)
      continue;
    kept[t] = true;
    complex.tetrahedra.push_back(static_cast<std::uint32_t>(t));
    cover(v, 4);
    for (const auto& e : kEdges)
      coveredEdges.insert(edgeKey(v[e[0]], v[e[1]]));
  }
  // Faces of discarded tetrahedra not shared with a kept one, each once.
  for (std::size_t t = 0; t < tets; ++t)
  {
    if (kept[t])
      continue;
    for (int f = 0; f < 4; ++f)
    {
      const std::uint32_t across = triangulation.neighbors[4 * t + f];
      if (across != kNoNeighbor && (kept[across >> 2] || (across >> 2) < t))
        continue;
      const std::uint32_t face[3] = {tv[4 * t + kFaceVertices[f][0]],
        tv[4 * t + kFaceVertices[f][1]], tv[4 * t + kFaceVertices[f][2]]};
      if (triangleCircumradius2(p(face[0]), p(face[1]), p(face[2])) <= alpha2)
      {
        complex.triangles.insert(complex.triangles.end(), face, face + 3);
        cover(face, 3);
      }
    }
  }
  for (std::size_t t = 0; t < tets; ++t)
  {
    if (kept[t])
      continue;
    for (const auto& e : kEdges)
    {
      const std::uint32_t edge[2] = {tv[4 * t + e[0]], tv[4 * t + e[1]]};
      if (coveredEdges.count(edgeKey(edge[0], edge[1])) == 0 &&
        distance2(p(edge[0]), p(edge[1])) * 0.25 <= alpha2)
      {
        complex.lines.insert(complex.lines.end(), edge, edge + 2);
        cover(edge, 2);
      }
    }
  }
  for (std::size_t i = 0; i < count; ++i)
    if (!used[i] && isFinite(p(i)))
      complex.vertices.push_back(static_cast<std::uint32_t>(i));
  return complex;
}

} // namespace fd3
