// Alpha shapes as vtkDelaunay3D defines them, over an exact Delaunay tetrahedralization: kept
// tetrahedra first, then the lower-dimensional simplices that no kept simplex already covers. On
// a regular tetrahedralization the radii are those of the smallest orthogonal spheres (weighted
// alpha shapes), and hidden points are in none of it.
// Unlike vtkDelaunay3D, whose bounding octahedron makes the hull faces it reports depend on cell
// numbering, every hull face is a candidate triangle here: the hull is exact.
//
// Each kind of simplex is found on every thread, a stretch of tetrahedra each, and listed in the
// order of a scan of the tetrahedra: a face by the lower-numbered of its two tetrahedra that are
// not kept, an edge by the lowest-numbered tetrahedron around it that is not kept. Whether an edge
// is covered (by a kept tetrahedron or a listed triangle) is read from the tetrahedra around it,
// turning about it through the neighbours: no shared set of edges, so no thread waits for another.
#include "TetMesh.h"
#include "fd3/Delaunay.h"
#include "fd3/Measures.h"
#include "system/Threads.h"

#include <atomic>
#include <cmath>
#include <memory>

namespace fd3
{
namespace
{
constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

class AlphaBuilder
{
public:
  AlphaBuilder(const double* xyz, const double* weights, std::size_t count,
    const Triangulation& triangulation, double alpha, ThreadTeam& team)
    : xyz_(xyz), weights_(weights), count_(count), t_(triangulation), alpha2_(alpha * alpha),
      tets_(triangulation.numberOfTetrahedra()), team_(team), kept_(tets_),
      used_(new std::atomic<std::uint8_t>[count]())
  {}

  AlphaComplex build()
  {
    AlphaComplex complex;
    team_.forRanges(tets_, "alpha", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
        kept_[t] = tetrahedronRadius2(t) <= alpha2_;
    });
    for (const std::uint32_t id : t_.hidden) // no vertex: no simplex of the complex
      used_[id].store(1, std::memory_order_relaxed);
    complex.tetrahedra = collect<IdArray>(tets_, [&](std::size_t t, auto& out) {
      if (!kept_[t])
        return;
      out.push_back(static_cast<std::uint32_t>(t));
      for (int i = 0; i < 4; ++i)
        markUsed(vertex(t, i));
    });
    complex.triangles = collect<std::vector<std::uint32_t>>(tets_, [&](std::size_t t, auto& out) {
      for (int f = 0; f < 4 && !kept_[t]; ++f)
        if (listsFace(t, f))
          for (int k = 0; k < 3; ++k)
            out.push_back(markUsed(vertex(t, kFaceVertices[f][k])));
    });
    complex.lines = collect<std::vector<std::uint32_t>>(tets_, [&](std::size_t t, auto& out) {
      for (int e = 0; e < 6 && !kept_[t]; ++e)
        if (listsEdge(t, kEdges[e][0], kEdges[e][1]))
          for (int k = 0; k < 2; ++k)
            out.push_back(markUsed(vertex(t, kEdges[e][k])));
    });
    complex.vertices = collect<std::vector<std::uint32_t>>(count_, [&](std::size_t i, auto& out) {
      if (!used_[i].load(std::memory_order_relaxed) && isFinite(p(std::uint32_t(i))))
        out.push_back(static_cast<std::uint32_t>(i));
    });
    return complex;
  }

private:
  const double* p(std::uint32_t id) const { return xyz_ + 3 * std::size_t(id); }
  std::uint32_t vertex(std::size_t t, int i) const { return t_.tetrahedra[4 * t + i]; }

  // Squared radii: circumradii, or for weighted points the smallest orthogonal spheres'.
  double tetrahedronRadius2(std::size_t t) const
  {
    const double* q[4] = {p(vertex(t, 0)), p(vertex(t, 1)), p(vertex(t, 2)), p(vertex(t, 3))};
    if (!weights_)
      return tetrahedronCircumradius2(q[0], q[1], q[2], q[3]);
    const double w[4] = {weights_[vertex(t, 0)], weights_[vertex(t, 1)], weights_[vertex(t, 2)],
      weights_[vertex(t, 3)]};
    return tetrahedronOrthoradius2(q, w);
  }
  double triangleRadius2(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
  {
    if (!weights_)
      return triangleCircumradius2(p(a), p(b), p(c));
    const double* q[3] = {p(a), p(b), p(c)};
    const double w[3] = {weights_[a], weights_[b], weights_[c]};
    return triangleOrthoradius2(q, w);
  }
  double edgeRadius2(std::uint32_t a, std::uint32_t b) const
  {
    return weights_ ? edgeOrthoradius2(p(a), p(b), weights_[a], weights_[b])
                    : distance2(p(a), p(b)) * 0.25;
  }
  std::uint32_t markUsed(std::uint32_t id)
  {
    used_[id].store(1, std::memory_order_relaxed);
    return id;
  }

  /// Each thread lists what emit(i, out) gives for its stretch of [0, n); the lists are joined in
  /// order.
  template <typename List, typename Emit>
  List collect(std::size_t n, Emit emit)
  {
    std::vector<std::vector<std::uint32_t>> parts(team_.partsFor(n));
    team_.forRanges(n, "alpha", [&](std::size_t k, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        emit(i, parts[k]);
    });
    List all;
    for (const auto& part : parts)
      all.insert(all.end(), part.begin(), part.end());
    return all;
  }

  /// Whether face f of t (not kept) is a triangle of the complex and t lists it: the other side is
  /// the hull or a tetrahedron not kept, and of two such, the lower-numbered one lists it.
  bool listsFace(std::size_t t, int f) const
  {
    const std::uint32_t across = t_.neighbors[4 * t + f];
    if (across != kNoNeighbor && (kept_[tetOf(across)] || tetOf(across) < t))
      return false;
    return isTriangle(t, f);
  }

  /// Whether face f of t, whose sides are not kept, is small enough to be a triangle.
  bool isTriangle(std::size_t t, int f) const
  {
    const int* q = kFaceVertices[f];
    return triangleRadius2(vertex(t, q[0]), vertex(t, q[1]), vertex(t, q[2])) <= alpha2_;
  }

  /// Whether the edge of t (not kept) on its vertices i and j is a line of the complex and t lists
  /// it: short enough, covered by no kept tetrahedron and no triangle around it, and t the
  /// lowest-numbered tetrahedron around it. Turns about the edge one way, then, where the hull
  /// opens it, the other way.
  bool listsEdge(std::size_t t, int i, int j) const
  {
    if (edgeRadius2(vertex(t, i), vertex(t, j)) > alpha2_)
      return false;
    const std::uint32_t a = vertex(t, i), b = vertex(t, j);
    // The two faces of t on the edge are those opposite its two other vertices.
    int others[2], n = 0;
    for (int k = 0; k < 4; ++k)
      if (k != i && k != j)
        others[n++] = k;
    for (const int start : others)
    {
      std::size_t tet = t;
      int face = start;
      for (;;)
      {
        // The face of `tet` opposite vertex `face` holds the edge; `tet` is not kept.
        const std::uint32_t across = t_.neighbors[4 * tet + face];
        if (across == kNoNeighbor)
        {
          if (isTriangle(tet, face))
            return false;
          break; // the hull: the other way round from t
        }
        const std::size_t next = tetOf(across);
        if (kept_[next] || next < t || isTriangle(tet, face))
          return false;
        if (next == t)
          return true; // all the way round
        // In `next`, the face entered is opposite faceOf(across); leave by the other face on the
        // edge: opposite the vertex that is neither a, b nor that one.
        int leave = 0;
        while (leave == faceOf(across) || vertex(next, leave) == a || vertex(next, leave) == b)
          ++leave;
        tet = next;
        face = leave;
      }
    }
    return true;
  }

  const double* xyz_;
  const double* weights_; // null: unweighted
  std::size_t count_;
  const Triangulation& t_;
  double alpha2_;
  std::size_t tets_;
  ThreadTeam& team_;
  std::vector<std::uint8_t> kept_; // each written by one thread, read after the fork-join
  std::unique_ptr<std::atomic<std::uint8_t>[]> used_; // several threads may mark one point
};
} // namespace

AlphaComplex alphaComplex(const double* xyz, std::size_t count, const Triangulation& triangulation,
  double alpha, int threads)
{
  return alphaComplex(xyz, nullptr, count, triangulation, alpha, threads);
}

AlphaComplex alphaComplex(const double* xyz, const double* weights, std::size_t count,
  const Triangulation& triangulation, double alpha, int threads)
{
  ThreadTeam team(boundedThreads(threads));
  return AlphaBuilder(xyz, weights, count, triangulation, alpha, team).build();
}

} // namespace fd3
