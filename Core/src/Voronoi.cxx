// Voronoi cells clipped to a box, from the exact Delaunay tetrahedralization.
//
// 1. The points are copied along a Hilbert curve, and eight far points, the corners of a cube
//    around the points and the box, join them: then every generator lies inside the hull, so its
//    cell is bounded and every ring of tetrahedra about one of its edges is closed. A box point x
//    is never nearer a far point f than its own generator p: |x - p| <= D, the diagonal of the
//    points and box together, while the corners lie at least 2 sqrt(3) D - D/2 > D from x. So
//    each cell's part inside the box is unchanged, and every face with a far point lies outside
//    the box.
// 2. The tetrahedra are renumbered in an order that the points alone decide (the mesh's own
//    varies with the thread count), and that keeps a star in a few stretches of memory.
// 3. Every tetrahedron's circumcentre, once (from its vertices in their sorted order, in
//    double-double where the tetrahedron is flat).
// 4. Per generator, along the curve, on the threads, a stretch of generators each (the cells do
//    not depend on how they are split):
//    - its star: the tetrahedra around it, gathered once through the faces that hold it, from
//      its lowest-numbered tetrahedron;
//    - its faces: the ring of star tetrahedra about each edge (p, q), turning counter-clockwise
//      about p -> q, so the face is counter-clockwise seen from outside; the faces in the order
//      the star shows the q, each ring from the tetrahedron that first showed q;
//    - a cell with a circumcentre outside the box is clipped by the box's six planes: each face
//      keeps its inside part, a crossing of an edge is computed from its two ends taken in
//      lexicographic order and put exactly on the plane (so the cells around that edge compute
//      the same point), and the crossings close a new face on the plane;
//    - volume and surface area, from each face's Newell vector.
// 5. The threads' stretches are joined in curve order. A cell's own vertices, numbered in the
//    order its faces meet them, are its crossings and the circumcentres it owns (those of the
//    tetrahedra whose lowest vertex is its generator), so the output's points too are in the
//    order of the cells.
#include "fd3/Voronoi.h"

#include "DoubleDouble.h"
#include "Geometry.h"
#include "InsertionOrder.h"
#include "Threads.h"
#include "fd3/Measures.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace fd3
{
namespace
{
constexpr std::uint32_t kNone = 0xFFFFFFFFu;
constexpr int kFarPoints = 8;
/// Marks a cell's own vertex (a crossing of the box) in a stretch's output, before the join
/// numbers it.
constexpr std::uint32_t kOwnVertex = 0x80000000u;

/// turn[i][j] = r: crossing the face opposite vertex r of a positive tetrahedron turns counter-
/// clockwise about its edge i -> j (r is the vertex for which (i, j, r, s) is an even permutation).
struct TurnTable
{
  int turn[4][4] = {};
};

constexpr TurnTable makeTurnTable()
{
  TurnTable table;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
    {
      if (i == j)
        continue;
      int k = 0;
      while (k == i || k == j)
        ++k;
      const int l = 6 - i - j - k;
      const int order[4] = {i, j, k, l};
      int inversions = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          inversions += order[a] > order[b];
      table.turn[i][j] = inversions % 2 == 0 ? k : l;
    }
  return table;
}
constexpr TurnTable kTurns = makeTurnTable();

/// An open-addressing map of 32-bit keys for one cell's work, emptied per cell in the time of
/// what it held.
class SmallMap
{
public:
  /// The value of `key`, inserting `value` when absent; `inserted` tells which.
  std::uint32_t find(std::uint32_t key, std::uint32_t value, bool& inserted)
  {
    if (2 * (used_.size() + 1) > slots_.size())
      grow();
    std::size_t slot = (std::uint64_t(key) * 0x9E3779B97F4A7C15ull >> 32) & mask_;
    while (slots_[slot].key != kNone && slots_[slot].key != key)
      slot = (slot + 1) & mask_;
    inserted = slots_[slot].key == kNone;
    if (inserted)
    {
      slots_[slot] = {key, value};
      used_.push_back(static_cast<std::uint32_t>(slot));
    }
    return slots_[slot].value;
  }
  bool insert(std::uint32_t key)
  {
    bool inserted;
    find(key, 0, inserted);
    return inserted;
  }
  void clear()
  {
    for (const std::uint32_t slot : used_)
      slots_[slot].key = kNone;
    used_.clear();
  }

private:
  struct Slot
  {
    std::uint32_t key = kNone, value = 0;
  };
  void grow()
  {
    std::vector<Slot> old(std::max<std::size_t>(256, 2 * slots_.size()));
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    const std::vector<std::uint32_t> used = std::move(used_);
    used_.clear();
    bool inserted;
    for (const std::uint32_t slot : used)
      find(old[slot].key, old[slot].value, inserted);
  }
  std::vector<Slot> slots_;
  std::vector<std::uint32_t> used_;
  std::size_t mask_ = 0;
};

/// The cells of one stretch of generators, with vertex ids that are tetrahedra (circumcentres
/// that other cells own) or kOwnVertex + the index of one of the stretch's own vertices.
struct Stretch
{
  std::vector<std::uint32_t> faceCounts; ///< per cell
  std::vector<std::uint32_t> faceSizes;  ///< per face
  std::vector<std::uint32_t> vertices;
  std::vector<std::uint32_t> neighbors; ///< per face
  std::vector<double> ownPoints;
  /// The circumcentres among the own vertices: tetrahedron, own index.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> ownedCentres;
  std::vector<double> volumes, areas;
};

/// A cell as a polyhedron of local vertices, while it is clipped.
struct Polyhedron
{
  std::vector<std::array<double, 3>> x;
  std::vector<std::uint32_t> tet;       ///< the tetrahedron of a circumcentre, kNone for a crossing
  std::vector<std::uint32_t> faceStart; ///< faces.size() + 1 entries
  std::vector<std::uint32_t> loops;
  std::vector<std::uint32_t> neighbors;
};

bool lexicographicallyLess(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] != b[0] ? a[0] < b[0] : (a[1] != b[1] ? a[1] < b[1] : a[2] < b[2]);
}

/// Builds one generator's cell after another (one builder per thread).
class CellBuilder
{
public:
  CellBuilder(const double* xyz, const std::vector<std::uint32_t>& inputId,
    const Triangulation& mesh, const std::vector<double>& centres,
    const std::vector<std::uint8_t>& inBox, const std::vector<std::uint32_t>& seeds,
    const std::array<double, 6>& box)
    : xyz_(xyz), inputId_(inputId), mesh_(mesh), centres_(centres), inBox_(inBox), seeds_(seeds),
      box_(box)
  {}

  void build(std::uint32_t generator, Stretch& out)
  {
    gatherStar(generator);
    traceFaces();
    bool inside = true;
    for (const StarTet& s : star_)
      inside = inside && s.inBox;
    if (inside)
      emitWhole(generator, out);
    else
    {
      makePolyhedron();
      for (int wall = 0; wall < 6 && !cell_.neighbors.empty(); ++wall)
        clip(wall);
      emitClipped(generator, out);
    }
  }

private:
  /// A tetrahedron of the generator's star, with what the cell needs of it, gathered once so
  /// that tracing the faces stays in a few cache lines.
  struct StarTet
  {
    std::uint32_t tet;
    std::uint32_t vertices[4];
    std::uint32_t next[4];  ///< star index across the face opposite each vertex but the generator
    std::uint32_t own;      ///< index among the cell's own vertices, once met (kNone before)
    std::uint8_t generator; ///< the generator's local index
    std::uint8_t entry;     ///< the vertex opposite the face it was reached through (4: none)
    bool owned;             ///< the generator is its lowest vertex: the cell owns its centre
    bool inBox;
    double centre[3];
  };

  std::uint32_t vertex(std::uint32_t t, int i) const { return mesh_.tetrahedra[4 * t + i]; }
  /// A face's neighbour as the output names it: the input id of a point, or a box wall.
  std::uint32_t inputId(std::uint32_t neighbor) const
  {
    return neighbor < inputId_.size() ? inputId_[neighbor] : neighbor;
  }
  /// The lowest vertex of t, whose cell owns its circumcentre: the first (sortTetrahedra).
  std::uint32_t owner(std::uint32_t t) const { return vertex(t, 0); }
  static int localIndex(const std::uint32_t* vertices, std::uint32_t v)
  {
    return (vertices[1] == v) + 2 * (vertices[2] == v) + 3 * (vertices[3] == v);
  }

  /// The tetrahedra around the generator, through the faces that hold it, into star_; each other
  /// vertex once into queue_, with a star tetrahedron that holds it.
  void gatherStar(std::uint32_t p)
  {
    star_.clear();
    localOf_.clear();
    seen_.clear();
    queue_.clear();
    bool inserted;
    localOf_.find(seeds_[p], 0, inserted);
    star_.emplace_back();
    star_.back().tet = seeds_[p];
    star_.back().entry = 4; // every vertex of the first tetrahedron is new
    for (std::size_t i = 0; i < star_.size(); ++i)
    {
      const std::uint32_t t = star_[i].tet;
      const std::uint32_t* v = &mesh_.tetrahedra[4 * std::size_t(t)];
      const std::uint32_t* n = &mesh_.neighbors[4 * std::size_t(t)];
      const int ip = localIndex(v, p);
      // A tetrahedron reached across a face brings one vertex not seen before at most: the one
      // opposite that face.
      for (int k = 0; k < 4; ++k)
        if (k != ip && (star_[i].entry == 4 || k == star_[i].entry) && seen_.insert(v[k]))
          queue_.push_back({v[k], static_cast<std::uint32_t>(i)});
      for (int k = 0; k < 4; ++k)
      {
        star_[i].vertices[k] = v[k];
        if (k == ip)
          continue;
        if (n[k] == kNoNeighbor) // far points surround every generator
          throw std::logic_error("voronoiCells: a generator's edge lies on the hull");
        const std::uint32_t across = n[k] >> 2;
        const auto index = static_cast<std::uint32_t>(star_.size());
        star_[i].next[k] = localOf_.find(across, index, inserted);
        if (inserted)
        {
          star_.emplace_back();
          star_.back().tet = across;
          star_.back().entry = static_cast<std::uint8_t>(n[k] & 3);
        }
      }
      StarTet& s = star_[i];
      s.generator = static_cast<std::uint8_t>(ip);
      s.owned = v[0] == p; // its lowest vertex
      s.inBox = inBox_[t];
      s.own = kNone;
      std::copy_n(centre(t), 3, s.centre);
    }
  }

  /// The ring of star tetrahedra about each edge (p, q), turning counter-clockwise about p -> q,
  /// into loops_ / faceStart_ / neighbors_, each from the tetrahedron that first showed q.
  void traceFaces()
  {
    loops_.clear();
    faceStart_.assign(1, 0);
    neighbors_.clear();
    for (const auto& [q, start] : queue_)
    {
      std::uint32_t i = start;
      do
      {
        const StarTet& s = star_[i];
        const int r = kTurns.turn[s.generator][localIndex(s.vertices, q)];
        loops_.push_back(i);
        i = s.next[r];
      } while (i != start);
      faceStart_.push_back(static_cast<std::uint32_t>(loops_.size()));
      neighbors_.push_back(q);
    }
  }

  const double* centre(std::uint32_t t) const { return &centres_[3 * std::size_t(t)]; }

  /// Adds a face's share of the cell's volume (six times: the face's Newell vector dotted with a
  /// vertex, both from the generator) and area (twice), the Newell vector summed over its edges.
  template <typename Corner>
  static void addFace(
    const double* g, std::uint32_t size, Corner corner, double& sixVolume, double& twiceArea)
  {
    double n[3] = {0, 0, 0};
    const double* first = corner(0);
    double a[3] = {first[0] - g[0], first[1] - g[1], first[2] - g[2]};
    const double a0[3] = {a[0], a[1], a[2]};
    for (std::uint32_t k = 1; k <= size; ++k)
    {
      const double* next = corner(k < size ? k : 0);
      const double b[3] = {next[0] - g[0], next[1] - g[1], next[2] - g[2]};
      n[0] += a[1] * b[2] - a[2] * b[1];
      n[1] += a[2] * b[0] - a[0] * b[2];
      n[2] += a[0] * b[1] - a[1] * b[0];
      a[0] = b[0];
      a[1] = b[1];
      a[2] = b[2];
    }
    sixVolume += n[0] * a0[0] + n[1] * a0[1] + n[2] * a0[2];
    twiceArea += std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }

  /// A cell inside the box: its faces are the rings as they are.
  void emitWhole(std::uint32_t p, Stretch& out)
  {
    const std::size_t faces = neighbors_.size();
    out.faceCounts.push_back(static_cast<std::uint32_t>(faces));
    std::size_t at = out.vertices.size();
    out.vertices.resize(at + loops_.size());
    std::uint32_t* vertices = out.vertices.data();
    const double* g = &xyz_[3 * std::size_t(p)];
    double sixVolume = 0, twiceArea = 0;
    for (std::uint32_t f = 0; f < faces; ++f)
    {
      const std::uint32_t size = faceStart_[f + 1] - faceStart_[f];
      out.faceSizes.push_back(size);
      out.neighbors.push_back(inputId(neighbors_[f]));
      const std::uint32_t* ring = &loops_[faceStart_[f]];
      for (std::uint32_t k = 0; k < size; ++k)
      {
        StarTet& s = star_[ring[k]];
        if (!s.owned)
          vertices[at++] = s.tet;
        else
        {
          if (s.own == kNone)
          {
            s.own = static_cast<std::uint32_t>(out.ownPoints.size() / 3);
            out.ownPoints.insert(out.ownPoints.end(), s.centre, s.centre + 3);
            out.ownedCentres.push_back({s.tet, s.own});
          }
          vertices[at++] = kOwnVertex | s.own;
        }
      }
      addFace(
        g, size, [&](std::uint32_t k) { return star_[ring[k]].centre; }, sixVolume, twiceArea);
    }
    out.volumes.push_back(sixVolume / 6);
    out.areas.push_back(twiceArea / 2);
  }

  void makePolyhedron()
  {
    Polyhedron& c = cell_;
    c.x.clear();
    c.tet.clear();
    c.loops.clear();
    c.faceStart.assign(1, 0);
    c.neighbors.clear();
    for (StarTet& s : star_)
      s.own = kNone;
    for (std::size_t f = 0; f + 1 < faceStart_.size(); ++f)
    {
      for (std::uint32_t k = faceStart_[f]; k < faceStart_[f + 1]; ++k)
      {
        StarTet& s = star_[loops_[k]];
        if (s.own == kNone)
        {
          s.own = static_cast<std::uint32_t>(c.x.size());
          c.x.push_back({s.centre[0], s.centre[1], s.centre[2]});
          c.tet.push_back(s.tet);
        }
        c.loops.push_back(s.own);
      }
      c.faceStart.push_back(static_cast<std::uint32_t>(c.loops.size()));
      c.neighbors.push_back(neighbors_[f]);
    }
  }

  /// Keeps the part of the cell on the box's side of wall `wall` (0..5: xmin, xmax, ..., zmax).
  void clip(int wall)
  {
    Polyhedron& c = cell_;
    const int axis = wall / 2;
    const double bound = box_[wall];
    auto outside = [&](std::uint32_t v) {
      return wall % 2 ? c.x[v][axis] > bound : c.x[v][axis] < bound;
    };
    auto on = [&](std::uint32_t v) { return c.x[v][axis] == bound; };
    bool anyOutside = false, anyInside = false;
    for (const std::uint32_t v : c.loops)
    {
      anyOutside = anyOutside || outside(v);
      anyInside = anyInside || (!outside(v) && !on(v));
    }
    if (!anyOutside)
      return;
    if (!anyInside) // the cell meets the box in a face, an edge, a point or nothing: no volume
    {
      c.loops.clear();
      c.faceStart.assign(1, 0);
      c.neighbors.clear();
      return;
    }
    crossings_.clear();
    capEdges_.clear();
    std::vector<std::uint32_t> loops, faceStart{0}, neighbors;
    for (std::size_t f = 0; f + 1 < c.faceStart.size(); ++f)
    {
      const std::uint32_t begin = c.faceStart[f], size = c.faceStart[f + 1] - begin;
      const std::size_t kept = loops.size();
      events_.clear();
      for (std::uint32_t k = 0; k < size; ++k)
      {
        const std::uint32_t u = c.loops[begin + k], w = c.loops[begin + (k + 1) % size];
        if (!outside(u))
          append(loops, kept, u);
        if (outside(u) == outside(w))
          continue;
        const std::uint32_t x = outside(u) ? (on(w) ? w : crossing(w, u, axis, bound))
                                           : (on(u) ? u : crossing(u, w, axis, bound));
        append(loops, kept, x);
        events_.push_back({x, outside(u)}); // entering when u lies outside
      }
      // The face now runs exit -> entry along the plane; the cap runs entry -> exit.
      for (std::size_t e = 0; e < events_.size(); ++e)
        if (!events_[e].second)
        {
          const auto& entry = events_[(e + 1) % events_.size()];
          if (entry.second && entry.first != events_[e].first)
            capEdges_.push_back({entry.first, events_[e].first});
        }
      if (loops.size() - kept >= 2 && loops.back() == loops[kept])
        loops.pop_back();
      if (loops.size() - kept >= 3)
      {
        faceStart.push_back(static_cast<std::uint32_t>(loops.size()));
        neighbors.push_back(c.neighbors[f]);
      }
      else
        loops.resize(kept);
    }
    closeCap(loops, faceStart, neighbors, kBoxFace + static_cast<std::uint32_t>(wall));
    c.loops.swap(loops);
    c.faceStart.swap(faceStart);
    c.neighbors.swap(neighbors);
  }

  static void append(std::vector<std::uint32_t>& loops, std::size_t kept, std::uint32_t v)
  {
    if (loops.size() == kept || loops.back() != v)
      loops.push_back(v);
  }

  /// The point where edge (inside, outside) crosses the plane, the same for every cell around it.
  std::uint32_t crossing(std::uint32_t inside, std::uint32_t outside, int axis, double bound)
  {
    for (const auto& known : crossings_)
      if ((known[0] == inside && known[1] == outside) ||
        (known[0] == outside && known[1] == inside))
        return known[2];
    std::array<double, 3> a = cell_.x[inside], b = cell_.x[outside];
    if (lexicographicallyLess(b, a))
      std::swap(a, b);
    const double t = (bound - a[axis]) / (b[axis] - a[axis]);
    std::array<double, 3> x;
    for (int k = 0; k < 3; ++k)
      x[k] = a[k] + t * (b[k] - a[k]);
    x[axis] = bound;
    const auto id = static_cast<std::uint32_t>(cell_.x.size());
    cell_.x.push_back(x);
    cell_.tet.push_back(kNone);
    crossings_.push_back({inside, outside, id});
    return id;
  }

  /// The new face on the plane: the cap edges chained into a loop. Where rounding cut a sliver of
  /// no width along an edge of the box, the edges make several loops: each becomes a face, and a
  /// loop of two edges (one there and back) none, so that every edge keeps its reverse.
  void closeCap(std::vector<std::uint32_t>& loops, std::vector<std::uint32_t>& faceStart,
    std::vector<std::uint32_t>& neighbors, std::uint32_t wall)
  {
    capUsed_.assign(capEdges_.size(), false);
    for (std::size_t first = 0; first < capEdges_.size(); ++first)
    {
      if (capUsed_[first])
        continue;
      const std::size_t kept = loops.size();
      std::size_t e = first;
      bool closed = false;
      while (e < capEdges_.size())
      {
        capUsed_[e] = true;
        loops.push_back(capEdges_[e].first);
        const std::uint32_t to = capEdges_[e].second;
        closed = to == capEdges_[first].first;
        if (closed)
          break;
        std::size_t k = 0;
        while (k < capEdges_.size() && (capUsed_[k] || capEdges_[k].first != to))
          ++k;
        e = k;
      }
      if (closed && loops.size() - kept >= 3)
      {
        faceStart.push_back(static_cast<std::uint32_t>(loops.size()));
        neighbors.push_back(wall);
      }
      else
        loops.resize(kept);
    }
  }

  /// A clipped cell into `out`: its own vertices (crossings and the circumcentres it owns)
  /// numbered in the order its faces meet them.
  void emitClipped(std::uint32_t p, Stretch& out)
  {
    const Polyhedron& c = cell_;
    const std::size_t faces = c.neighbors.size();
    out.faceCounts.push_back(static_cast<std::uint32_t>(faces));
    localOf_.clear();
    const double* g = &xyz_[3 * std::size_t(p)];
    double sixVolume = 0, twiceArea = 0;
    for (std::size_t f = 0; f < faces; ++f)
    {
      const std::uint32_t begin = c.faceStart[f], size = c.faceStart[f + 1] - begin;
      out.faceSizes.push_back(size);
      out.neighbors.push_back(inputId(c.neighbors[f]));
      for (std::uint32_t k = 0; k < size; ++k)
      {
        const std::uint32_t v = c.loops[begin + k], t = c.tet[v];
        if (t != kNone && owner(t) != p)
        {
          out.vertices.push_back(t);
          continue;
        }
        bool inserted;
        const auto own = static_cast<std::uint32_t>(out.ownPoints.size() / 3);
        const std::uint32_t id = localOf_.find(v, own, inserted);
        if (inserted)
        {
          out.ownPoints.insert(out.ownPoints.end(), c.x[v].begin(), c.x[v].end());
          if (t != kNone)
            out.ownedCentres.push_back({t, id});
        }
        out.vertices.push_back(kOwnVertex | id);
      }
      addFace(
        g, size, [&](std::uint32_t k) { return c.x[c.loops[begin + k]].data(); }, sixVolume,
        twiceArea);
    }
    out.volumes.push_back(sixVolume / 6);
    out.areas.push_back(twiceArea / 2);
  }

  const double* xyz_;
  const std::vector<std::uint32_t>& inputId_;
  const Triangulation& mesh_;
  const std::vector<double>& centres_;
  const std::vector<std::uint8_t>& inBox_;
  const std::vector<std::uint32_t>& seeds_;
  const std::array<double, 6> box_;
  // One cell's scratch, kept between cells for its memory.
  std::vector<std::uint32_t> loops_, faceStart_, neighbors_;
  std::vector<StarTet> star_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> queue_;
  SmallMap seen_, localOf_;
  Polyhedron cell_;
  std::vector<std::array<std::uint32_t, 3>> crossings_;
  std::vector<std::pair<std::uint32_t, bool>> events_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> capEdges_;
  std::vector<bool> capUsed_;
};

/// The bounding box of the finite points, in VTK's order; false when there is none.
bool finiteBounds(const double* xyz, std::size_t count, std::array<double, 6>& bounds)
{
  std::size_t i = 0;
  while (i < count && !isFinite(xyz + 3 * i))
    ++i;
  if (i == count)
    return false;
  Box box = Box::around(xyz + 3 * i);
  for (; i < count; ++i)
    if (isFinite(xyz + 3 * i))
      box.include(xyz + 3 * i);
  bounds = {box.lo[0], box.hi[0], box.lo[1], box.hi[1], box.lo[2], box.hi[2]};
  return true;
}

bool isBox(const std::array<double, 6>& b)
{
  for (int a = 0; a < 3; ++a)
    if (!(b[2 * a] <= b[2 * a + 1]) || !std::isfinite(b[2 * a]) || !std::isfinite(b[2 * a + 1]))
      return false;
  return true;
}

/// The input's points along a Hilbert curve through their bounding box (exact copies in the
/// order of their ids): the generators, then the points that only bound their cells (so that a
/// tetrahedron with a generator has one as its lowest vertex, the owner of its centre), then the
/// points that are not finite; then the corners of a cube about the points and the box (see the
/// top of this file). Neighbouring points, and so the tetrahedra between them, then lie near each
/// other in memory.
struct CurvePoints
{
  std::vector<double> xyz;            ///< empty when the corners are not finite
  std::vector<std::uint32_t> inputId; ///< of each point but the corners
};

CurvePoints alongCurve(ThreadTeam& team, const double* xyz, std::size_t count,
  std::size_t generators, const std::array<double, 6>& points, const std::array<double, 6>& box)
{
  double both[6], centre[3], scale[3];
  const double cells = double(1u << kHilbertBits);
  for (int a = 0; a < 3; ++a)
  {
    both[2 * a] = std::min(points[2 * a], box[2 * a]);
    both[2 * a + 1] = std::max(points[2 * a + 1], box[2 * a + 1]);
    centre[a] = both[2 * a] / 2 + both[2 * a + 1] / 2;
    const double extent = points[2 * a + 1] - points[2 * a];
    scale[a] = extent > 0 && std::isfinite(extent) ? cells / extent : 0;
  }
  double reach = 2 * diagonal(both);
  if (reach == 0)
    reach = 1; // one point and a box of no volume: any cube will do
  CurvePoints curve;
  curve.xyz.resize(3 * (count + kFarPoints));
  for (int k = 0; k < kFarPoints; ++k)
    for (int a = 0; a < 3; ++a)
    {
      const double x = centre[a] + ((k >> a) & 1 ? reach : -reach);
      if (!std::isfinite(x))
        return {};
      curve.xyz[3 * (count + k) + a] = x;
    }
  std::vector<std::uint64_t> keys(count);
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* p = xyz + 3 * i;
      std::uint64_t position = std::uint64_t(1) << 32; // after every finite point
      if (isFinite(p))
      {
        std::uint32_t cell[3];
        for (int a = 0; a < 3; ++a)
          cell[a] = static_cast<std::uint32_t>(
            std::min(cells - 1, std::max(0.0, (p[a] - points[2 * a]) * scale[a])));
        position = hilbertIndex(cell[0], cell[1], cell[2]);
        if (i >= generators) // after every generator: see circumcentres' owners
          position |= std::uint64_t(1) << (3 * kHilbertBits);
      }
      keys[i] = position << 31 | i; // ids below 2^30
    }
  });
  std::sort(keys.begin(), keys.end());
  curve.inputId.resize(count);
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const auto id = static_cast<std::uint32_t>(keys[k] & ((std::uint64_t(1) << 31) - 1));
      curve.inputId[k] = id;
      std::copy_n(xyz + 3 * std::size_t(id), 3, &curve.xyz[3 * k]);
    }
  });
  return curve;
}

/// The circumcentre's offset from the first vertex, in double-double from the exact edges (each
/// scaled by `down`, a power of two): for flat tetrahedra, whose offset in doubles loses the
/// digits that cancel in its determinants.
void circumcentreInDoubleDouble(
  const double* xyz, const std::uint32_t* ids, double down, double up, double* offset)
{
  DoubleDouble e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
    {
      e[i][k] = DoubleDouble::difference(
        xyz[3 * std::size_t(ids[i + 1]) + k], xyz[3 * std::size_t(ids[0]) + k]);
      e[i][k].hi *= down;
      e[i][k].lo *= down;
    }
  auto crossDD = [](const DoubleDouble* a, const DoubleDouble* b, DoubleDouble* out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
  };
  auto dotDD = [](const DoubleDouble* a, const DoubleDouble* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  DoubleDouble vw[3], wu[3], uv[3];
  crossDD(e[1], e[2], vw);
  crossDD(e[2], e[0], wu);
  crossDD(e[0], e[1], uv);
  const DoubleDouble uu = dotDD(e[0], e[0]), vv = dotDD(e[1], e[1]), ww = dotDD(e[2], e[2]);
  const double twiceVolume = 2 * dotDD(e[0], vw).value();
  if (twiceVolume == 0)
    return;
  for (int k = 0; k < 3; ++k)
    offset[k] = (uu * vw[k] + vv * wu[k] + ww * uv[k]).value() / twiceVolume * up;
}

/// Adds to `a` (the first vertex's coordinates) the circumcentre's offset from it, computed on
/// edges scaled by a power of two (exact) to a length near 1, so that their squares and cubes
/// neither underflow nor overflow at any magnitude of the input; in double-double where the
/// tetrahedron is flat enough for doubles to lose the offset's digits.
void addScaledCircumcentre(const double* xyz, const std::uint32_t* ids, double* a)
{
  // Below this volume over the product of the edges, the offset in doubles is off by more than
  // 1e-13 of the edges.
  constexpr double kFlat = 1e-3;
  double edges[3][3], longest = 0;
  for (int e = 0; e < 3; ++e)
    for (int k = 0; k < 3; ++k)
    {
      edges[e][k] = xyz[3 * std::size_t(ids[e + 1]) + k] - xyz[3 * std::size_t(ids[0]) + k];
      longest = std::max(longest, std::fabs(edges[e][k]));
    }
  if (!(longest > 0) || !std::isfinite(longest))
    return;
  const int exponent = std::ilogb(longest);
  const bool normal = exponent > -1000 && exponent < 1000; // 2^-exponent is a double
  const double down = normal ? std::ldexp(1.0, -exponent) : 0, up = normal ? 1 / down : 0;
  for (auto& edge : edges)
    for (double& x : edge)
      x = normal ? x * down : std::ldexp(x, -exponent);
  const Circumcentre c = circumcentreOfEdges(edges[0], edges[1], edges[2]);
  double offset[3];
  for (int k = 0; k < 3; ++k)
    offset[k] = normal ? c.offset[k] * up : std::ldexp(c.offset[k], exponent);
  if (normal && std::fabs(c.sixVolume) < kFlat * std::sqrt(c.edgeProduct2))
    circumcentreInDoubleDouble(xyz, ids, down, up, offset);
  for (int k = 0; k < 3; ++k)
    a[k] += offset[k];
}

/// Renumbers the tetrahedra, and their vertices, in an order that the points alone decide: each
/// tetrahedron's vertices ascending (the last two swapped where that keeps it positive), the
/// tetrahedra by those vertices. The mesh's own order varies with the thread count; everything
/// built from the sorted one is the same for any. And as the points lie along a curve, a
/// generator's star then lies in a few stretches of memory, the tetrahedra whose centres its cell
/// owns in one.
void sortTetrahedra(ThreadTeam& team, Triangulation& mesh, std::size_t vertices)
{
  const std::size_t tets = mesh.numberOfTetrahedra();
  const std::uint32_t* t4 = mesh.tetrahedra.data();
  // Each tetrahedron's vertices in their new order, and where each old local index goes.
  IdArray tetrahedra(4 * tets);
  std::vector<std::uint8_t> moves(tets); // 2 bits per old local index
  team.forRanges(tets, "voronoi sort", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      // A sorting network of five exchanges; each exchange flips the orientation.
      int order[4] = {0, 1, 2, 3};
      bool odd = false;
      auto exchange = [&](int i, int j) {
        if (t4[4 * t + order[j]] < t4[4 * t + order[i]])
        {
          std::swap(order[i], order[j]);
          odd = !odd;
        }
      };
      exchange(0, 1);
      exchange(2, 3);
      exchange(0, 2);
      exchange(1, 3);
      exchange(1, 2);
      if (odd)
        std::swap(order[2], order[3]);
      std::uint8_t move = 0;
      for (int k = 0; k < 4; ++k)
      {
        tetrahedra[4 * t + k] = t4[4 * t + order[k]];
        move |= std::uint8_t(k << (2 * order[k]));
      }
      moves[t] = move;
    }
  });
  // By the lowest vertex (a counting sort), then by the others within each lowest vertex.
  std::vector<std::uint32_t> start(vertices + 1, 0), sorted(tets);
  for (std::size_t t = 0; t < tets; ++t)
    ++start[tetrahedra[4 * t] + 1];
  for (std::size_t v = 0; v < vertices; ++v)
    start[v + 1] += start[v];
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < tets; ++t)
      sorted[next[tetrahedra[4 * t]]++] = static_cast<std::uint32_t>(t);
  }
  std::vector<std::uint32_t> newId(tets);
  team.forRanges(vertices, "voronoi sort", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      auto before = [&](std::uint32_t a, std::uint32_t b) {
        const std::uint32_t* x = &tetrahedra[4 * std::size_t(a)];
        const std::uint32_t* y = &tetrahedra[4 * std::size_t(b)];
        return x[1] != y[1] ? x[1] < y[1] : (x[2] != y[2] ? x[2] < y[2] : x[3] < y[3]);
      };
      // Insertion sort: a vertex is the lowest of a few tetrahedra.
      for (std::uint32_t k = start[v] + 1; k < start[v + 1]; ++k)
      {
        const std::uint32_t moving = sorted[k];
        std::uint32_t at = k;
        for (; at > start[v] && before(moving, sorted[at - 1]); --at)
          sorted[at] = sorted[at - 1];
        sorted[at] = moving;
      }
      for (std::uint32_t k = start[v]; k < start[v + 1]; ++k)
        newId[sorted[k]] = k;
    }
  });
  IdArray sortedTetrahedra(4 * tets), neighbors(4 * tets);
  team.forRanges(tets, "voronoi sort", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const std::size_t t = sorted[k];
      std::copy_n(&tetrahedra[4 * t], 4, &sortedTetrahedra[4 * k]);
      for (int i = 0; i < 4; ++i)
      {
        const std::uint32_t across = mesh.neighbors[4 * t + i];
        const std::uint32_t to = across == kNoNeighbor
          ? kNoNeighbor
          : newId[across >> 2] << 2 | ((moves[across >> 2] >> 2 * (across & 3)) & 3);
        neighbors[4 * k + ((moves[t] >> 2 * i) & 3)] = to;
      }
    }
  });
  mesh.tetrahedra.swap(sortedTetrahedra);
  mesh.neighbors.swap(neighbors);
}

/// Every tetrahedron's circumcentre, and whether it lies in the closed box.
void circumcentres(ThreadTeam& team, const double* xyz, const Triangulation& mesh,
  const std::array<double, 6>& box, std::vector<double>& centres, std::vector<std::uint8_t>& inBox)
{
  const std::size_t tets = mesh.numberOfTetrahedra();
  centres.resize(3 * tets);
  inBox.resize(tets);
  const auto* t4 = mesh.tetrahedra.data();
  team.forRanges(tets, "circumcentres", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      // From the vertices in their sorted order (sortTetrahedra), which the thread count does
      // not change, so neither does the centre's rounding.
      double* x = &centres[3 * t];
      std::copy_n(xyz + 3 * std::size_t(t4[4 * t]), 3, x);
      addScaledCircumcentre(xyz, t4 + 4 * t, x);
      inBox[t] = x[0] >= box[0] && x[0] <= box[1] && x[1] >= box[2] && x[1] <= box[3] &&
        x[2] >= box[4] && x[2] <= box[5];
    }
  });
}

/// The lowest-numbered tetrahedron of each vertex's star.
std::vector<std::uint32_t> starSeeds(
  ThreadTeam& team, const Triangulation& mesh, std::size_t vertices)
{
  std::unique_ptr<std::atomic<std::uint32_t>[]> lowest(new std::atomic<std::uint32_t>[vertices]);
  for (std::size_t v = 0; v < vertices; ++v)
    lowest[v].store(kNone, std::memory_order_relaxed);
  team.forRanges(
    mesh.numberOfTetrahedra(), "stars", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
        for (int i = 0; i < 4; ++i)
        {
          std::atomic<std::uint32_t>& seed = lowest[mesh.tetrahedra[4 * t + i]];
          std::uint32_t known = seed.load(std::memory_order_relaxed);
          while (t < known &&
            !seed.compare_exchange_weak(
              known, static_cast<std::uint32_t>(t), std::memory_order_relaxed))
          {}
        }
    });
  std::vector<std::uint32_t> seeds(vertices);
  for (std::size_t v = 0; v < vertices; ++v)
    seeds[v] = lowest[v].load(std::memory_order_relaxed);
  return seeds;
}

/// Joins the stretches, in order, into `cells`, the circumcentres that other cells own numbered
/// through `pointOf` (a scratch of a number per tetrahedron).
void join(ThreadTeam& team, std::vector<Stretch>& parts, std::vector<std::uint32_t>& pointOf,
  VoronoiCells& cells)
{
  const std::size_t n = parts.size();
  std::vector<std::size_t> cellAt(n + 1, 0), faceAt(n + 1, 0), vertexAt(n + 1, 0),
    pointAt(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    cellAt[k + 1] = cellAt[k] + parts[k].faceCounts.size();
    faceAt[k + 1] = faceAt[k] + parts[k].faceSizes.size();
    vertexAt[k + 1] = vertexAt[k] + parts[k].vertices.size();
    pointAt[k + 1] = pointAt[k] + parts[k].ownPoints.size() / 3;
  }
  if (pointAt[n] >= kOwnVertex)
    throw std::length_error("voronoiCells: more than 2^31 vertices");
  cells.points.resize(3 * pointAt[n]);
  cells.cellFaces.resize(cellAt[n] + 1);
  cells.faceStart.resize(faceAt[n] + 1);
  cells.faceVertices.resize(vertexAt[n]);
  cells.faceNeighbors.resize(faceAt[n]);
  cells.volumes.resize(cellAt[n]);
  cells.areas.resize(cellAt[n]);
  cells.cellFaces[cellAt[n]] = faceAt[n];
  cells.faceStart[faceAt[n]] = vertexAt[n];
  ThreadedWork& record = team.newRecord("voronoi join");
  team.run(
    n,
    [&](std::size_t k) {
      for (const auto& [t, own] : parts[k].ownedCentres)
        pointOf[t] = static_cast<std::uint32_t>(pointAt[k] + own);
    },
    record);
  team.run(
    n,
    [&](std::size_t k) {
      const Stretch& s = parts[k];
      std::size_t face = faceAt[k];
      for (std::size_t c = 0; c < s.faceCounts.size(); ++c)
      {
        cells.cellFaces[cellAt[k] + c] = face;
        face += s.faceCounts[c];
      }
      std::size_t vertex = vertexAt[k];
      for (std::size_t f = 0; f < s.faceSizes.size(); ++f)
      {
        cells.faceStart[faceAt[k] + f] = vertex;
        vertex += s.faceSizes[f];
      }
      for (std::size_t v = 0; v < s.vertices.size(); ++v)
      {
        const std::uint32_t id = s.vertices[v];
        cells.faceVertices[vertexAt[k] + v] = id & kOwnVertex
          ? static_cast<std::uint32_t>(pointAt[k] + (id & ~kOwnVertex))
          : pointOf[id];
      }
      std::copy(s.neighbors.begin(), s.neighbors.end(), cells.faceNeighbors.begin() + faceAt[k]);
      std::copy(s.ownPoints.begin(), s.ownPoints.end(), cells.points.begin() + 3 * pointAt[k]);
      std::copy(s.volumes.begin(), s.volumes.end(), cells.volumes.begin() + cellAt[k]);
      std::copy(s.areas.begin(), s.areas.end(), cells.areas.begin() + cellAt[k]);
      parts[k] = Stretch();
    },
    record);
}
} // namespace

std::size_t VoronoiCells::numberOfNeighbors(std::size_t cell) const
{
  return static_cast<std::size_t>(std::count_if(faceNeighbors.begin() + cellFaces[cell],
    faceNeighbors.begin() + cellFaces[cell + 1], [](std::uint32_t q) { return q < kBoxFace; }));
}

VoronoiCells voronoiCells(const double* xyz, std::size_t count, const VoronoiOptions& options)
{
  VoronoiCells cells;
  cells.cellFaces.assign(1, 0);
  cells.faceStart.assign(1, 0);
  cells.stats.inputPoints = count;
  std::array<double, 6> bounds;
  if (!finiteBounds(xyz, count, bounds))
  {
    cells.status = Status::Empty;
    cells.stats.nonFinitePoints = count;
    return cells;
  }
  cells.box = isBox(options.box) ? options.box : bounds;
  ThreadTeam team(boundedThreads(options.threads));
  const CurvePoints curve = alongCurve(team, xyz, count, options.generators, bounds, cells.box);
  if (curve.xyz.empty())
  {
    cells.status = Status::OutOfRange;
    return cells;
  }

  Options delaunay;
  delaunay.threads = options.threads;
  delaunay.progress = options.progress;
  Triangulation mesh = triangulate(curve.xyz.data(), count + kFarPoints, delaunay);
  cells.stats = mesh.stats;
  cells.stats.inputPoints -= kFarPoints;
  cells.stats.insertedPoints -= kFarPoints;
  if (mesh.status != Status::Ok)
  {
    cells.status = mesh.status;
    return cells;
  }

  std::vector<double> centres;
  std::vector<std::uint8_t> inBox;
  sortTetrahedra(team, mesh, count + kFarPoints);
  circumcentres(team, curve.xyz.data(), mesh, cells.box, centres, inBox);
  const std::vector<std::uint32_t> seeds = starSeeds(team, mesh, count + kFarPoints);
  std::vector<std::uint32_t> vertices; // the generators, as the mesh numbers them
  for (std::uint32_t v = 0; v < count; ++v)
    if (mesh.representative[v] == v && curve.inputId[v] < options.generators)
      vertices.push_back(v);
  cells.generators.resize(vertices.size());
  for (std::size_t c = 0; c < vertices.size(); ++c)
    cells.generators[c] = curve.inputId[vertices[c]];
  std::vector<Stretch> parts(team.partsFor(vertices.size()));
  team.forRanges(
    vertices.size(), "voronoi cells", [&](std::size_t k, std::size_t begin, std::size_t end) {
      CellBuilder builder(curve.xyz.data(), curve.inputId, mesh, centres, inBox, seeds, cells.box);
      for (std::size_t c = begin; c < end; ++c)
        builder.build(vertices[c], parts[k]);
    });
  std::vector<double>().swap(centres);
  std::vector<std::uint32_t> pointOf(mesh.numberOfTetrahedra());
  join(team, parts, pointOf, cells);
  return cells;
}

} // namespace fd3
