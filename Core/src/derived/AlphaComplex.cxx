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
//
// A periodic tetrahedralization is walked the same way once its faces are paired across the box:
// its tetrahedra are placed (PeriodicPlacement), each in a frame of its own, so a vertex is known
// across a face by its input point and its shift relative to the face's, not by its id. Where a
// tetrahedron holds two images of one point (a box of very few points), a simplex can be met
// twice, as two translates: the lists are then reduced to one of each.
#include "TetMesh.h"
#include "fd3/Delaunay.h"
#include "fd3/Measures.h"
#include "fd3/Periodic.h"
#include "system/Threads.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <set>
#include <vector>

namespace fd3
{
namespace
{
constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

/// A tetrahedralization as the builder walks it: tetrahedra on point ids, their coordinates, and
/// the neighbours across faces (Triangulation::neighbors' codes).
class PlainMesh
{
public:
  PlainMesh(const double* xyz, const Triangulation& t) : xyz_(xyz), t_(t) {}

  std::size_t tetrahedra() const { return t_.numberOfTetrahedra(); }
  std::uint32_t vertex(std::size_t t, int i) const { return t_.tetrahedra[4 * t + i]; }
  const double* point(std::uint32_t id) const { return xyz_ + 3 * std::size_t(id); }
  /// The input point at a vertex id.
  std::uint32_t source(std::uint32_t id) const { return id; }
  std::uint32_t neighbor(std::size_t t, int f) const { return t_.neighbors[4 * t + f]; }
  /// The index in `next` (across face f of t) of t's vertex i, a vertex of that face.
  int across(std::size_t t, int, int i, std::size_t next) const
  {
    int k = 0;
    while (vertex(next, k) != vertex(t, i))
      ++k;
    return k;
  }
  const std::vector<std::uint32_t>& hidden() const { return t_.hidden; }
  static constexpr bool kTranslates = false;

private:
  const double* xyz_;
  const Triangulation& t_;
};

/// A periodic tetrahedralization placed for drawing: ids below `count` are input points at their
/// own positions, the rest images. Faces are paired by their vertices' input points and shifts
/// relative to the face's least vertex (least point, then least shift), which every translate of
/// the face shares.
class PeriodicMesh
{
public:
  using Shift = std::array<std::int32_t, 3>;

  /// `hidden`: the input points that are no vertex (weighted points), ascending.
  PeriodicMesh(const double* xyz, std::size_t count, const PeriodicPlacement& placement,
    const std::vector<std::uint32_t>& hidden)
    : xyz_(xyz), count_(count), p_(placement), hidden_(hidden),
      neighbors_(placement.tetrahedra.size(), kNoNeighbor)
  {
    pairFaces();
    for (std::size_t t = 0; t < tetrahedra() && !repeats_; ++t)
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
          repeats_ = repeats_ || source(vertex(t, i)) == source(vertex(t, j));
  }

  std::size_t tetrahedra() const { return p_.tetrahedra.size() / 4; }
  std::uint32_t vertex(std::size_t t, int i) const { return p_.tetrahedra[4 * t + i]; }
  const double* point(std::uint32_t id) const
  {
    return id < count_ ? xyz_ + 3 * std::size_t(id) : &p_.imagePoints[3 * (id - count_)];
  }
  std::uint32_t source(std::uint32_t id) const
  {
    return id < count_ ? id : p_.imageSources[id - count_];
  }
  Shift shift(std::uint32_t id) const
  {
    if (id < count_)
      return {0, 0, 0};
    const std::int32_t* s = &p_.imageShifts[3 * std::size_t(id - count_)];
    return {s[0], s[1], s[2]};
  }
  std::uint32_t neighbor(std::size_t t, int f) const { return neighbors_[4 * t + f]; }
  int across(std::size_t t, int f, int i, std::size_t next) const
  {
    const std::uint32_t code = neighbor(t, f);
    const Shift here = shift(leastVertex(t, f)), there = shift(leastVertex(next, faceOf(code)));
    Shift wanted = shift(vertex(t, i));
    for (int a = 0; a < 3; ++a)
      wanted[a] += there[a] - here[a];
    int k = 0;
    while (k == faceOf(code) || source(vertex(next, k)) != source(vertex(t, i)) ||
      shift(vertex(next, k)) != wanted)
      ++k;
    return k;
  }
  const std::vector<std::uint32_t>& hidden() const { return hidden_; }
  static constexpr bool kTranslates = true;
  /// Whether a tetrahedron holds two images of one point, so that a simplex can be listed as two
  /// of its translates.
  bool listsTranslates() const { return repeats_; }

  /// A triangle's or edge's vertices (`size` of them) by input point and shift from the least
  /// vertex, sorted, then zeros: the same for every translate.
  using Key = std::array<std::int64_t, 12>;
  Key key(const std::uint32_t* ids, int size) const
  {
    std::uint32_t least = ids[0];
    for (int k = 1; k < size; ++k)
      if (before(ids[k], least))
        least = ids[k];
    const Shift origin = shift(least);
    std::array<std::array<std::int64_t, 4>, 3> vertices{};
    for (int k = 0; k < size; ++k)
    {
      const Shift s = shift(ids[k]);
      vertices[k] = {source(ids[k]), s[0] - origin[0], s[1] - origin[1], s[2] - origin[2]};
    }
    std::sort(vertices.begin(), vertices.begin() + size);
    Key flat{};
    for (int k = 0; k < size; ++k)
      std::copy(vertices[k].begin(), vertices[k].end(), flat.begin() + 4 * k);
    return flat;
  }

private:
  bool before(std::uint32_t a, std::uint32_t b) const
  {
    return source(a) != source(b) ? source(a) < source(b) : shift(a) < shift(b);
  }
  std::uint32_t leastVertex(std::size_t t, int f) const
  {
    const int* q = kFaceVertices[f];
    std::uint32_t least = vertex(t, q[0]);
    for (int k = 1; k < 3; ++k)
      if (before(vertex(t, q[k]), least))
        least = vertex(t, q[k]);
    return least;
  }
  Key faceKey(std::size_t t, int f) const
  {
    const int* q = kFaceVertices[f];
    const std::uint32_t ids[3] = {vertex(t, q[0]), vertex(t, q[1]), vertex(t, q[2])};
    return key(ids, 3);
  }

  /// Each face with the other tetrahedron's that holds a translate of it (none along a free
  /// axis's hull): faces sorted by a hash of their keys, then paired within equal hashes.
  void pairFaces()
  {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> faces(p_.tetrahedra.size());
    for (std::size_t code = 0; code < faces.size(); ++code)
    {
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (const std::int64_t x : faceKey(code / 4, int(code % 4)))
        h = (h ^ std::uint64_t(x)) * 0x100000001B3ull;
      faces[code] = {h, std::uint32_t(code)};
    }
    std::sort(faces.begin(), faces.end());
    for (std::size_t begin = 0, end; begin < faces.size(); begin = end)
    {
      for (end = begin + 1; end < faces.size() && faces[end].first == faces[begin].first; ++end)
        ;
      for (std::size_t a = begin; a < end; ++a)
        for (std::size_t b = a + 1; b < end && neighbors_[faces[a].second] == kNoNeighbor; ++b)
        {
          const std::uint32_t ca = faces[a].second, cb = faces[b].second;
          if (neighbors_[cb] == kNoNeighbor &&
            faceKey(ca / 4, int(ca % 4)) == faceKey(cb / 4, int(cb % 4)))
          {
            neighbors_[ca] = cb;
            neighbors_[cb] = ca;
          }
        }
    }
  }

  const double* xyz_;
  std::size_t count_;
  const PeriodicPlacement& p_;
  const std::vector<std::uint32_t>& hidden_;
  std::vector<std::uint32_t> neighbors_;
  bool repeats_ = false;
};

template <typename Mesh>
class AlphaBuilder
{
public:
  /// `sources`: the points that vertices are images of, the `count` whose unused ones are
  /// vertices of the complex and a piece's ghosts.
  AlphaBuilder(const Mesh& mesh, const double* weights, std::size_t count, std::size_t sources,
    double alpha, ThreadTeam& team)
    : mesh_(mesh), weights_(weights), count_(count), alpha2_(alpha * alpha),
      tets_(mesh.tetrahedra()), team_(team), kept_(tets_),
      used_(new std::atomic<std::uint8_t>[std::max(count, sources)]())
  {}

  AlphaComplex build()
  {
    AlphaComplex complex;
    team_.forRanges(tets_, "alpha", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
        kept_[t] = tetrahedronRadius2(t) <= alpha2_;
    });
    for (const std::uint32_t id : mesh_.hidden()) // no vertex: no simplex of the complex
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
    if constexpr (Mesh::kTranslates)
      if (mesh_.listsTranslates())
      {
        complex.triangles = oneOfEachTranslate(std::move(complex.triangles), 3);
        complex.lines = oneOfEachTranslate(std::move(complex.lines), 2);
      }
    return complex;
  }

private:
  const double* p(std::uint32_t id) const { return mesh_.point(id); }
  std::uint32_t vertex(std::size_t t, int i) const { return mesh_.vertex(t, i); }

  // Squared radii: circumradii, or for weighted points the smallest orthogonal spheres'.
  double tetrahedronRadius2(std::size_t t) const
  {
    const double* q[4] = {p(vertex(t, 0)), p(vertex(t, 1)), p(vertex(t, 2)), p(vertex(t, 3))};
    if (!weights_)
      return tetrahedronCircumradius2(q[0], q[1], q[2], q[3]);
    const double w[4] = {
      weight(vertex(t, 0)), weight(vertex(t, 1)), weight(vertex(t, 2)), weight(vertex(t, 3))};
    return tetrahedronOrthoradius2(q, w);
  }
  double triangleRadius2(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
  {
    if (!weights_)
      return triangleCircumradius2(p(a), p(b), p(c));
    const double* q[3] = {p(a), p(b), p(c)};
    const double w[3] = {weight(a), weight(b), weight(c)};
    return triangleOrthoradius2(q, w);
  }
  double edgeRadius2(std::uint32_t a, std::uint32_t b) const
  {
    return weights_ ? edgeOrthoradius2(p(a), p(b), weight(a), weight(b))
                    : distance2(p(a), p(b)) * 0.25;
  }
  /// A vertex's weight, its input point's (an image has its point's).
  double weight(std::uint32_t id) const { return weights_[mesh_.source(id)]; }
  std::uint32_t markUsed(std::uint32_t id)
  {
    used_[mesh_.source(id)].store(1, std::memory_order_relaxed);
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

  /// The simplices of `size` vertices in `list`, the first of each set of translates.
  std::vector<std::uint32_t> oneOfEachTranslate(std::vector<std::uint32_t> list, int size) const
  {
    std::set<typename Mesh::Key> seen;
    std::size_t kept = 0;
    for (std::size_t s = 0; s < list.size(); s += size)
      if (seen.insert(mesh_.key(&list[s], size)).second)
        kept += std::copy(&list[s], &list[s] + size, &list[kept]) - &list[kept];
    list.resize(kept);
    return list;
  }

  /// Whether face f of t (not kept) is a triangle of the complex and t lists it: the other side is
  /// the hull or a tetrahedron not kept, and of two such, the lower-numbered one lists it.
  bool listsFace(std::size_t t, int f) const
  {
    const std::uint32_t across = mesh_.neighbor(t, f);
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
  /// opens it, the other way, following the edge's ends by their index in each tetrahedron.
  bool listsEdge(std::size_t t, int i, int j) const
  {
    if (edgeRadius2(vertex(t, i), vertex(t, j)) > alpha2_)
      return false;
    // The two faces of t on the edge are those opposite its two other vertices.
    int others[2], n = 0;
    for (int k = 0; k < 4; ++k)
      if (k != i && k != j)
        others[n++] = k;
    for (const int start : others)
    {
      std::size_t tet = t;
      int face = start, a = i, b = j;
      for (;;)
      {
        // The face of `tet` opposite vertex `face` holds the edge, its ends a and b; `tet` is not
        // kept.
        const std::uint32_t across = mesh_.neighbor(tet, face);
        if (across == kNoNeighbor)
        {
          if (isTriangle(tet, face))
            return false;
          break; // the hull: the other way round from t
        }
        const std::size_t next = tetOf(across);
        if (kept_[next] || next < t || isTriangle(tet, face))
          return false;
        const int nextA = mesh_.across(tet, face, a, next),
                  nextB = mesh_.across(tet, face, b, next);
        if (next == t && std::min(nextA, nextB) == std::min(i, j) &&
          std::max(nextA, nextB) == std::max(i, j))
          return true; // all the way round
        // In `next`, the face entered is opposite faceOf(across); leave by the other face on the
        // edge: opposite the vertex that is neither end nor that one.
        int leave = 0;
        while (leave == faceOf(across) || leave == nextA || leave == nextB)
          ++leave;
        tet = next;
        face = leave;
        a = nextA;
        b = nextB;
      }
    }
    return true;
  }

  const Mesh& mesh_;
  const double* weights_; // null: unweighted
  std::size_t count_;
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
  const PlainMesh mesh(xyz, triangulation);
  return AlphaBuilder<PlainMesh>(mesh, weights, count, count, alpha, team).build();
}

AlphaComplex alphaComplex(const double* xyz, std::size_t count, const PeriodicPlacement& placement,
  double alpha, int threads)
{
  return alphaComplex(xyz, nullptr, count, placement, {}, alpha, threads);
}

AlphaComplex alphaComplex(const double* xyz, const double* weights, std::size_t count,
  const PeriodicPlacement& placement, const std::vector<std::uint32_t>& hidden, double alpha,
  int threads)
{
  ThreadTeam team(boundedThreads(threads));
  const PeriodicMesh mesh(xyz, count, placement, hidden);
  std::size_t sources = count; // a piece's images are also of its ghosts, after its points
  for (const std::uint32_t source : placement.imageSources)
    sources = std::max<std::size_t>(sources, source + 1);
  return AlphaBuilder<PeriodicMesh>(mesh, weights, count, sources, alpha, team).build();
}

} // namespace fd3
