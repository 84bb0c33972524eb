// Voronoi cells clipped to a box, from the exact Delaunay tetrahedralization.
//
// 1. The points are copied along a Hilbert curve, and eight far points, the corners of a cube
//    around the points and the box, join them: then every generator lies inside the hull, so its
//    cell is bounded and every ring of tetrahedra about one of its edges is closed. A box point x
//    is never nearer a far point f than its own generator p: |x - p| <= D, the diagonal of the
//    points and box together, while the corners lie at least 2 sqrt(3) D - D/2 > D from x. So
//    each cell's part inside the box is unchanged, and every face with a far point lies outside
//    the box.
// 2. Each tetrahedron's vertices are put in ascending order (orientation kept), an order that the
//    points alone decide (the mesh's own varies with the thread count), and its circumcentre is
//    computed once, from its vertices in that order (in double-double where it is flat).
// 3. The stars: the tetrahedra around each vertex, listed in two passes (a count, then the ids),
//    each thread keeping the vertices of its own range; beside them, the centres in the box that
//    each generator's cell owns (those of the tetrahedra whose lowest vertex it is) and whether
//    any centre of its star lies outside the box.
// 4. A cell's faces, per generator p: the ring of its star's tetrahedra about each edge (p, q),
//    turning counter-clockwise about p -> q, so the face is counter-clockwise seen from outside;
//    each ring from the tetrahedron after its lowest link vertex, the faces by q. Where each ring
//    starts and the order of the faces follow from the points alone, so the cells do not depend
//    on the thread count or on how the generators are split among the threads.
// 5. The cells that leave the box first, on the threads: clipped by the box's six planes, each
//    face keeps its inside part, a crossing of an edge is computed from its two ends taken in
//    lexicographic order and put exactly on the plane (so the cells around that edge compute the
//    same point), and the crossings close a new face on the plane. With their sizes known (a
//    whole cell with a star of n tetrahedra has 2 + n/2 faces and 3n face vertices), every cell
//    has its place in the output: the centres each cell owns are numbered there, and the whole
//    cells are written straight into their places. Volume and surface area come from each face's
//    Newell vector.
#include "fd3/Voronoi.h"

#include "DoubleDouble.h"
#include "Geometry.h"
#include "InsertionOrder.h"
#include "Threads.h"
#include "fd3/Distributed.h"
#include "fd3/Measures.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace fd3
{
namespace
{
constexpr std::uint32_t kNone = 0xFFFFFFFFu;
using Doubles = VoronoiCells::Doubles;
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
/// The local indices of a tetrahedron's vertices but one.
constexpr int kOthers[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

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

/// The clipped cells of one stretch of generators, with vertex ids that are tetrahedra (their
/// circumcentres) or kOwnVertex + the index of one of the cell's crossings of the box.
struct Stretch
{
  std::vector<std::uint32_t> cells;      ///< index of each cell among all
  std::vector<std::uint32_t> faceCounts; ///< per cell
  std::vector<std::uint32_t> crossings;  ///< per cell
  std::vector<std::uint32_t> faceSizes;  ///< per face
  std::vector<std::uint32_t> vertices;
  std::vector<std::uint32_t> neighbors; ///< per face
  std::vector<double> crossingPoints;
  std::vector<double> volumes, areas;
};

/// The tetrahedra around each vertex: those of vertex v are tets[start[v], start[v + 1]), the
/// ownedCentres[v] ones whose centres its cell owns first, each part in the mesh's order; beside
/// them, what each vertex needs to know of its star before its cell is built.
struct Stars
{
  std::vector<std::size_t> start;
  IdArray tets;
  /// The tetrahedra whose lowest vertex it is and whose centre lies in the box: the centres its
  /// cell owns and numbers.
  std::vector<std::uint32_t> ownedCentres;
  /// Whether a tetrahedron of its star has its centre outside the box: its cell is clipped.
  std::vector<std::uint8_t> clipped;
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

/// What every cell is built from, shared by the threads (read only while cells are built).
struct CellSources
{
  const double* xyz;                         ///< the points, along the curve
  const std::vector<std::uint32_t>& inputId; ///< of each point but the far ones
  const std::uint32_t* tetrahedra;           ///< 4 vertices each, in sortVertices' order
  const Stars& stars;
  const std::vector<std::uint8_t>& inBox; ///< per tetrahedron: its centre lies in the closed box
  const std::array<double, 6>& box;
  /// Per tetrahedron: its centre, while the clipped cells are built; then null, and the centres
  /// in the box are read from `points` through `pointOf`.
  const double* centres = nullptr;
  const std::uint32_t* pointOf = nullptr; ///< per tetrahedron whose centre is an output point
  const double* points = nullptr;
};

/// Builds one generator's cell after another (one builder per thread).
class CellBuilder
{
public:
  /// A builder for cells of a mesh of `vertices` vertices.
  CellBuilder(const CellSources& sources, std::size_t vertices)
    : in_(sources), linkOf_(vertices, kNoLink)
  {}

  /// The faces of p's cell before any clipping: the ring of its star's tetrahedra about each edge
  /// (p, q), turning counter-clockwise about p -> q (so the face is counter-clockwise seen from
  /// outside), from the tetrahedron after the lowest vertex of the ring; the faces by q, lowest
  /// first. The rings as sets are the mesh's; where each starts, and the order of the faces,
  /// depend on the points alone.
  void trace(std::uint32_t p)
  {
    gatherStar(p);
    linkEdges();
    traceRings();
  }

  /// A cell inside the box, written where `at` says: its faces are the rings as they are.
  void emitWhole(
    std::uint32_t p, std::size_t cell, std::size_t face, std::size_t vertex, VoronoiCells& out)
  {
    if (neighbors_.size() != 2 + star_.size() / 2 || loops_.size() != 3 * star_.size())
      throw std::logic_error("voronoiCells: a generator's link is not a sphere");
    for (StarTet& s : star_)
      s.point = in_.pointOf[s.tet];
    const double* g = in_.xyz + 3 * std::size_t(p);
    double sixVolume = 0, twiceArea = 0;
    out.cellFaces[cell] = face;
    for (std::size_t f = 0; f < neighbors_.size(); ++f, ++face)
    {
      const std::uint32_t size = faceStart_[f + 1] - faceStart_[f];
      const std::uint32_t* ring = &loops_[faceStart_[f]];
      out.faceStart[face] = vertex;
      out.faceNeighbors[face] = inputId(neighbors_[f]);
      for (std::uint32_t k = 0; k < size; ++k)
        out.faceVertices[vertex++] = star_[ring[k]].point;
      addFace(
        g, size,
        [&](std::uint32_t k) { return in_.points + 3 * std::size_t(star_[ring[k]].point); },
        sixVolume, twiceArea);
    }
    out.volumes[cell] = sixVolume / 6;
    out.areas[cell] = twiceArea / 2;
  }

  /// A cell that leaves the box, clipped by its six planes, into `out`.
  void emitClipped(std::uint32_t p, std::uint32_t cell, Stretch& out)
  {
    makePolyhedron();
    for (int wall = 0; wall < 6 && !cell_.neighbors.empty(); ++wall)
      clip(wall);
    const Polyhedron& c = cell_;
    const std::size_t faces = c.neighbors.size();
    out.cells.push_back(cell);
    out.faceCounts.push_back(static_cast<std::uint32_t>(faces));
    crossingOf_.clear();
    const double* g = in_.xyz + 3 * std::size_t(p);
    double sixVolume = 0, twiceArea = 0;
    std::uint32_t crossings = 0;
    for (std::size_t f = 0; f < faces; ++f)
    {
      const std::uint32_t begin = c.faceStart[f], size = c.faceStart[f + 1] - begin;
      out.faceSizes.push_back(size);
      out.neighbors.push_back(inputId(c.neighbors[f]));
      for (std::uint32_t k = 0; k < size; ++k)
      {
        const std::uint32_t v = c.loops[begin + k], t = c.tet[v];
        if (t != kNone)
        {
          out.vertices.push_back(t);
          continue;
        }
        bool inserted;
        const std::uint32_t id = crossingOf_.find(v, crossings, inserted);
        if (inserted)
        {
          ++crossings;
          out.crossingPoints.insert(out.crossingPoints.end(), c.x[v].begin(), c.x[v].end());
        }
        out.vertices.push_back(kOwnVertex | id);
      }
      addFace(
        g, size, [&](std::uint32_t k) { return c.x[c.loops[begin + k]].data(); }, sixVolume,
        twiceArea);
    }
    out.crossings.push_back(crossings);
    out.volumes.push_back(sixVolume / 6);
    out.areas.push_back(twiceArea / 2);
  }

private:
  /// A tetrahedron of the generator's star.
  struct StarTet
  {
    std::uint32_t tet;
    std::uint32_t vertices[4];
    std::uint32_t link[4];  ///< each other vertex's index in link_
    std::uint32_t point;    ///< its centre's output point, once looked up
    std::uint8_t generator; ///< the generator's local index
  };
  /// A tetrahedron's step in the ring about (p, q): from its face with link vertex `from` to its
  /// face with `to`, in the turning order. `cell` tells the cell that wrote it.
  struct RingStep
  {
    std::uint32_t to, star, cell;
  };

  /// A face's neighbour as the output names it: the input id of a point, or a box wall.
  std::uint32_t inputId(std::uint32_t neighbor) const
  {
    return neighbor < in_.inputId.size() ? in_.inputId[neighbor] : neighbor;
  }
  static int localIndex(const std::uint32_t* vertices, std::uint32_t v)
  {
    return (vertices[1] == v) + 2 * (vertices[2] == v) + 3 * (vertices[3] == v);
  }
  const double* centre(std::uint32_t t) const
  {
    return in_.centres ? in_.centres + 3 * std::size_t(t)
                       : in_.points + 3 * std::size_t(in_.pointOf[t]);
  }

  void gatherStar(std::uint32_t p)
  {
    star_.clear();
    for (std::size_t k = in_.stars.start[p]; k < in_.stars.start[p + 1]; ++k)
    {
      StarTet s;
      s.tet = in_.stars.tets[k];
      const std::uint32_t* v = in_.tetrahedra + 4 * std::size_t(s.tet);
      for (int k = 0; k < 4; ++k) // a loop, not a call to memmove
        s.vertices[k] = v[k];
      s.generator = static_cast<std::uint8_t>(localIndex(s.vertices, p));
      star_.push_back(s);
    }
  }

  /// The generator's link (the vertices it is joined to) into link_, and each star
  /// tetrahedron's step in the ring about each of its other three vertices.
  void linkEdges()
  {
    // A star of n tetrahedra has 2 + n/2 link vertices: below kDenseStar, their indices fit
    // linkOf_'s 16 bits.
    const bool dense = star_.size() < kDenseStar;
    if (!dense)
      linkOfLarge_.clear();
    link_.resize(3 * star_.size() + 1);
    links_ = 0;
    for (StarTet& s : star_)
      for (const int k : kOthers[s.generator])
        s.link[k] = dense ? denseLinkIndex(s.vertices[k]) : largeLinkIndex(s.vertices[k]);
    link_.resize(links_);
    if (dense)
      for (const std::uint32_t v : link_)
        linkOf_[v] = kNoLink;
    ++stamp_;
    if (links_ <= kDenseLinks && steps_.size() < links_ * links_)
      steps_.resize(links_ * links_, {0, 0, 0});
    else if (links_ > kDenseLinks)
      stepsLarge_.clear();
    firstFrom_.assign(links_, kNone);
    firstId_.assign(links_, kNone);
    for (std::size_t i = 0; i < star_.size(); ++i)
    {
      const StarTet& s = star_[i];
      for (const int k : kOthers[s.generator])
      {
        // Crossing the face opposite r, the one with the fourth vertex, turns counter-clockwise
        // about p -> q: the ring enters through the face with r and leaves through the other.
        const int r = kTurns.turn[s.generator][k], fourth = 6 - s.generator - k - r;
        const std::uint32_t q = s.link[k], from = s.link[r];
        step(q, from) = {s.link[fourth], static_cast<std::uint32_t>(i), stamp_};
        // Without a branch: whether a vertex is lower than the ring's lowest so far is a coin
        // toss.
        const bool lower = s.vertices[r] < firstId_[q];
        firstId_[q] = lower ? s.vertices[r] : firstId_[q];
        firstFrom_[q] = lower ? from : firstFrom_[q];
      }
    }
  }

  /// v's index in link_, which it joins if new (without a branch: new or not is a coin toss).
  std::uint32_t denseLinkIndex(std::uint32_t v)
  {
    std::uint16_t& index = linkOf_[v];
    link_[links_] = v;
    const bool added = index == kNoLink;
    index = added ? static_cast<std::uint16_t>(links_) : index;
    links_ += added;
    return index;
  }

  std::uint32_t largeLinkIndex(std::uint32_t v)
  {
    const auto found = linkOfLarge_.emplace(v, static_cast<std::uint32_t>(links_));
    if (found.second)
      link_[links_++] = v;
    return found.first->second;
  }

  RingStep& step(std::uint32_t q, std::uint32_t from)
  {
    const std::size_t links = link_.size();
    return links <= kDenseLinks ? steps_[q * links + from]
                                : stepsLarge_[std::uint64_t(q) << 32 | from];
  }

  /// The rings, into loops_ / faceStart_ / neighbors_.
  void traceRings()
  {
    orderFaces();
    const std::size_t links = link_.size(), longest = star_.size();
    loops_.resize(3 * longest);
    faceStart_.resize(links + 1);
    neighbors_.resize(links);
    std::uint32_t* loop = loops_.data();
    const RingStep* steps = steps_.data();
    const std::uint32_t stamp = stamp_;
    std::size_t at = 0;
    faceStart_[0] = 0;
    for (std::size_t f = 0; f < links; ++f)
    {
      const std::uint32_t q = order_[f], first = firstFrom_[q];
      const std::size_t begin = at;
      std::uint32_t from = first;
      do
      {
        const RingStep& next = links <= kDenseLinks ? steps[q * links + from] : step(q, from);
        if (next.cell != stamp || at - begin >= longest || at == loops_.size())
          throw std::logic_error("voronoiCells: a ring about an edge is open");
        loop[at++] = next.star;
        from = next.to;
      } while (from != first);
      faceStart_[f + 1] = static_cast<std::uint32_t>(at);
      neighbors_[f] = link_[q];
    }
    loops_.resize(at);
  }

  /// The link vertices by id into order_: each one's rank among them, counted without a branch
  /// where the link is small, sorted where it is large.
  void orderFaces()
  {
    const std::size_t links = link_.size();
    order_.resize(links);
    std::uint32_t* order = order_.data();
    if (links <= kCountedLinks)
    {
      // Vertex ids are below 2^31: signed comparisons, which vectorize.
      ids_.assign(link_.begin(), link_.end());
      const std::int32_t* ids = ids_.data();
      for (std::uint32_t q = 0; q < links; ++q)
      {
        const std::int32_t id = ids[q];
        std::int32_t rank = 0;
        for (std::size_t other = 0; other < links; ++other)
          rank += ids[other] < id;
        order[rank] = q;
      }
      return;
    }
    for (std::uint32_t q = 0; q < links; ++q)
      order[q] = q;
    std::sort(order_.begin(), order_.end(),
      [&](std::uint32_t a, std::uint32_t b) { return link_[a] < link_[b]; });
  }

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

  void makePolyhedron()
  {
    Polyhedron& c = cell_;
    c.x.clear();
    c.tet.clear();
    c.loops.clear();
    c.faceStart.assign(1, 0);
    c.neighbors.clear();
    localOf_.clear();
    for (std::size_t f = 0; f + 1 < faceStart_.size(); ++f)
    {
      for (std::uint32_t k = faceStart_[f]; k < faceStart_[f + 1]; ++k)
      {
        const StarTet& s = star_[loops_[k]];
        bool inserted;
        const std::uint32_t v =
          localOf_.find(loops_[k], static_cast<std::uint32_t>(c.x.size()), inserted);
        if (inserted)
        {
          const double* x = centre(s.tet);
          c.x.push_back({x[0], x[1], x[2]});
          c.tet.push_back(s.tet);
        }
        c.loops.push_back(v);
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
    const double bound = in_.box[wall];
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

  /// Stars of fewer tetrahedra number their link in linkOf_; link vertices up to this many
  /// have their ring steps in a square table.
  static constexpr std::size_t kDenseStar = 1 << 16;
  static constexpr std::size_t kDenseLinks = 256;
  /// Up to this many link vertices, the faces' order is counted rather than sorted.
  static constexpr std::size_t kCountedLinks = 64;
  static constexpr std::uint16_t kNoLink = 0xFFFF;

  const CellSources& in_;
  // One cell's scratch, kept between cells for its memory.
  std::vector<StarTet> star_;
  std::vector<std::uint32_t> link_; ///< the vertices joined to the generator, as met
  /// Each vertex's index in link_ while a cell is traced (kNoLink otherwise): two bytes a vertex
  /// per thread, against a hash map's several lookups.
  std::vector<std::uint16_t> linkOf_;
  std::unordered_map<std::uint32_t, std::uint32_t> linkOfLarge_;
  std::vector<RingStep> steps_; ///< links x links, by (q, from)
  std::unordered_map<std::uint64_t, RingStep> stepsLarge_;
  std::uint32_t stamp_ = 0;
  /// Per link vertex: the lowest `from` of its ring, and its vertex id.
  std::vector<std::uint32_t> firstFrom_, firstId_;
  std::vector<std::uint32_t> order_; ///< the link vertices by vertex id
  std::vector<std::int32_t> ids_;
  std::size_t links_ = 0; ///< link_'s length while it is gathered
  SmallMap localOf_, crossingOf_;
  std::vector<std::uint32_t> loops_, faceStart_, neighbors_;
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
      for (int a = 0; a < 3; ++a)
        curve.xyz[3 * k + a] = xyz[3 * std::size_t(id) + a];
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

/// The tetrahedralization of the points, then of the far points, in one frame. Inserted last,
/// the far points meet the points' hull in a few tests; inserted among the points, they would take
/// part in the tests of every insertion near the hull, in exact arithmetic where its faces hold
/// cocircular points (a lattice's), which no sphere through a far point tells apart. With
/// options.density, `density` gets each point's densities() value in the points' own
/// tetrahedralization, before the far points change the tetrahedra near the hull.
Triangulation meshOf(const CurvePoints& curve, std::size_t count, const VoronoiOptions& options,
  std::vector<double>& density)
{
  Options delaunay;
  delaunay.threads = options.threads;
  delaunay.progress = options.progress;
  delaunay.computeNeighbors = false; // the stars are listed instead
  IncrementalDelaunay mesh(
    curve.xyz.data(), count, delaunay, frameOf(curve.xyz.data(), count + kFarPoints), kFarPoints);
  if (mesh.status() == Status::Aborted)
    return mesh.release();
  if (options.density)
    density = densities(curve.xyz.data(), count, mesh.snapshot());
  mesh.add(curve.xyz.data() + 3 * count, kFarPoints);
  return mesh.release();
}

/// Each tetrahedron's vertices in ascending order, the last two exchanged where that order is an
/// odd permutation of the mesh's, so that it stays positively oriented; then its circumcentre,
/// from the vertices in that order, and whether it lies in the closed box. The mesh's rotation of
/// the vertices varies with the thread count; this order, the centres' rounding and everything
/// built from them depend on the points alone.
void prepareTetrahedra(ThreadTeam& team, const double* xyz, Triangulation& mesh,
  const std::array<double, 6>& box, Doubles& centres, std::vector<std::uint8_t>& inBox)
{
  const std::size_t tets = mesh.numberOfTetrahedra();
  centres.resize(3 * tets);
  inBox.resize(tets);
  std::uint32_t* t4 = mesh.tetrahedra.data();
  team.forRanges(tets, "circumcentres", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      std::uint32_t* v = t4 + 4 * t;
      // A sorting network of five exchanges; each exchange flips the orientation.
      bool odd = false;
      auto exchange = [&](int i, int j) {
        if (v[j] < v[i])
        {
          std::swap(v[i], v[j]);
          odd = !odd;
        }
      };
      exchange(0, 1);
      exchange(2, 3);
      exchange(0, 2);
      exchange(1, 3);
      exchange(1, 2);
      if (odd)
        std::swap(v[2], v[3]);
      double* x = &centres[3 * t];
      for (int a = 0; a < 3; ++a)
        x[a] = xyz[3 * std::size_t(v[0]) + a];
      addScaledCircumcentre(xyz, v, x);
      inBox[t] = x[0] >= box[0] && x[0] <= box[1] && x[1] >= box[2] && x[1] <= box[3] &&
        x[2] >= box[4] && x[2] <= box[5];
    }
  });
}

/// Every vertex's star, in two passes over the tetrahedra (a count, then their ids). Each thread
/// scans every tetrahedron for the vertices of its own range, so that no two threads write one
/// vertex's lists, and a list is in the mesh's order for any thread count.
Stars starsOf(ThreadTeam& team, const Triangulation& mesh, const std::vector<std::uint8_t>& inBox,
  std::size_t vertices)
{
  Stars stars;
  const std::size_t tets = mesh.numberOfTetrahedra();
  const std::uint32_t* t4 = mesh.tetrahedra.data();
  stars.start.assign(vertices + 1, 0);
  stars.ownedCentres.assign(vertices, 0);
  stars.clipped.assign(vertices, 0);
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      if (v[0] >= lo && v[0] < hi)
        stars.ownedCentres[v[0]] += inBox[t];
      for (int k = 0; k < 4; ++k)
        if (v[k] >= lo && v[k] < hi)
        {
          ++stars.start[v[k] + 1];
          stars.clipped[v[k]] |= !inBox[t];
        }
    }
  });
  for (std::size_t v = 0; v < vertices; ++v)
    stars.start[v + 1] += stars.start[v];
  stars.tets.resize(4 * tets);
  // Each star's owned tetrahedra first.
  std::vector<std::size_t> owned(stars.start.begin(), stars.start.end() - 1), others(vertices);
  for (std::size_t v = 0; v < vertices; ++v)
    others[v] = stars.start[v] + stars.ownedCentres[v];
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      if (v[0] >= lo && v[0] < hi)
        stars.tets[inBox[t] ? owned[v[0]]++ : others[v[0]]++] = static_cast<std::uint32_t>(t);
      for (int k = 1; k < 4; ++k)
        if (v[k] >= lo && v[k] < hi)
          stars.tets[others[v[k]]++] = static_cast<std::uint32_t>(t);
    }
  });
  return stars;
}

/// Where each cell's parts go in the output: its first face, vertex, centre and crossing.
struct CellPlaces
{
  std::vector<std::size_t> vertex, centre, crossing;
};

/// The sizes of the cells (those of the clipped ones from their stretches; a whole cell with a
/// star of n tetrahedra has 2 + n/2 faces, those of its link, a sphere, and 3n face vertices),
/// summed into places, and the output's arrays made to hold them.
CellPlaces placeCells(const std::vector<std::uint32_t>& vertices, const Stars& stars,
  const std::vector<Stretch>& parts, VoronoiCells& cells)
{
  const std::size_t n = vertices.size();
  std::vector<std::uint32_t> clippedAt(n, kNone); // the cell's index in its stretch
  std::vector<std::uint32_t> clippedPart(n, kNone);
  for (std::size_t k = 0; k < parts.size(); ++k)
    for (std::size_t j = 0; j < parts[k].cells.size(); ++j)
    {
      clippedAt[parts[k].cells[j]] = static_cast<std::uint32_t>(j);
      clippedPart[parts[k].cells[j]] = static_cast<std::uint32_t>(k);
    }
  std::vector<std::size_t> clippedFace(parts.size(), 0);
  CellPlaces at;
  at.vertex.resize(n + 1);
  at.centre.resize(n + 1);
  at.crossing.resize(n + 1);
  cells.cellFaces.resize(n + 1);
  cells.cellFaces[0] = at.vertex[0] = at.centre[0] = at.crossing[0] = 0;
  for (std::size_t c = 0; c < n; ++c)
  {
    const std::uint32_t p = vertices[c];
    std::size_t faces, faceVertices, crossings = 0;
    if (clippedAt[c] == kNone)
    {
      const std::size_t star = stars.start[p + 1] - stars.start[p];
      faces = 2 + star / 2;
      faceVertices = 3 * star;
    }
    else
    {
      const Stretch& s = parts[clippedPart[c]];
      const std::uint32_t j = clippedAt[c];
      faces = s.faceCounts[j];
      std::size_t& face = clippedFace[clippedPart[c]];
      faceVertices = std::accumulate(
        s.faceSizes.begin() + face, s.faceSizes.begin() + face + faces, std::size_t(0));
      face += faces;
      crossings = s.crossings[j];
    }
    cells.cellFaces[c + 1] = cells.cellFaces[c] + faces;
    at.vertex[c + 1] = at.vertex[c] + faceVertices;
    at.centre[c + 1] = at.centre[c] + stars.ownedCentres[p];
    at.crossing[c + 1] = at.crossing[c] + crossings;
  }
  const std::size_t points = at.centre[n] + at.crossing[n];
  if (points >= kOwnVertex)
    throw std::length_error("voronoiCells: more than 2^31 vertices");
  for (std::size_t& crossing : at.crossing)
    crossing += at.centre[n];
  cells.faceStart.resize(cells.cellFaces[n] + 1);
  cells.faceStart[cells.cellFaces[n]] = at.vertex[n];
  cells.faceVertices.resize(at.vertex[n]);
  cells.faceNeighbors.resize(cells.cellFaces[n]);
  cells.points.resize(3 * points);
  cells.volumes.resize(n);
  cells.areas.resize(n);
  return at;
}

/// The output's points of the centres in the box, cell after cell: each cell's own (those of the
/// tetrahedra whose lowest vertex is its generator) by their tetrahedra's other vertices; and
/// the point of each such tetrahedron.
void placeCentres(ThreadTeam& team, const std::vector<std::uint32_t>& vertices,
  const CellSources& in, const CellPlaces& at, const Doubles& centres, IdArray& pointOf,
  VoronoiCells& cells)
{
  team.forRanges(
    vertices.size(), "voronoi centres", [&](std::size_t, std::size_t begin, std::size_t end) {
      std::vector<std::uint32_t> owned;
      for (std::size_t c = begin; c < end; ++c)
      {
        const std::uint32_t p = vertices[c];
        const auto first = in.stars.tets.begin() + std::ptrdiff_t(in.stars.start[p]);
        owned.assign(first, first + in.stars.ownedCentres[p]);
        std::sort(owned.begin(), owned.end(), [&](std::uint32_t a, std::uint32_t b) {
          return std::lexicographical_compare(in.tetrahedra + 4 * std::size_t(a) + 1,
            in.tetrahedra + 4 * std::size_t(a) + 4, in.tetrahedra + 4 * std::size_t(b) + 1,
            in.tetrahedra + 4 * std::size_t(b) + 4);
        });
        for (std::size_t r = 0; r < owned.size(); ++r)
        {
          const std::size_t point = at.centre[c] + r;
          pointOf[owned[r]] = static_cast<std::uint32_t>(point);
          for (int a = 0; a < 3; ++a)
            cells.points[3 * point + a] = centres[3 * std::size_t(owned[r]) + a];
        }
      }
    });
}

/// The clipped cells' stretches into the output, their circumcentres numbered through pointOf.
void copyClipped(ThreadTeam& team, std::vector<Stretch>& parts, const CellPlaces& at,
  const IdArray& pointOf, VoronoiCells& cells)
{
  team.run(
    parts.size(),
    [&](std::size_t k) {
      const Stretch& s = parts[k];
      std::size_t face = 0, vertex = 0;
      for (std::size_t j = 0; j < s.cells.size(); ++j)
      {
        const std::size_t c = s.cells[j];
        std::size_t outFace = cells.cellFaces[c], outVertex = at.vertex[c];
        for (std::uint32_t f = 0; f < s.faceCounts[j]; ++f, ++face, ++outFace)
        {
          cells.faceStart[outFace] = outVertex;
          cells.faceNeighbors[outFace] = s.neighbors[face];
          for (std::uint32_t i = 0; i < s.faceSizes[face]; ++i, ++vertex)
          {
            const std::uint32_t id = s.vertices[vertex];
            cells.faceVertices[outVertex++] = id & kOwnVertex
              ? static_cast<std::uint32_t>(at.crossing[c] + (id & ~kOwnVertex))
              : pointOf[id];
          }
        }
        cells.volumes[c] = s.volumes[j];
        cells.areas[c] = s.areas[j];
      }
      std::size_t crossing = 0;
      for (std::size_t j = 0; j < s.cells.size(); ++j)
      {
        const std::size_t c = s.cells[j], size = 3 * s.crossings[j];
        std::copy_n(
          s.crossingPoints.data() + crossing, size, cells.points.data() + 3 * at.crossing[c]);
        crossing += size;
      }
      parts[k] = Stretch();
    },
    team.newRecord("voronoi clipped"));
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

  std::vector<double> density;
  Triangulation mesh = meshOf(curve, count, options, density);
  cells.stats = mesh.stats;
  cells.stats.inputPoints -= kFarPoints;
  cells.stats.insertedPoints -= kFarPoints;
  if (mesh.status != Status::Ok)
  {
    cells.status = mesh.status;
    return cells;
  }

  Doubles centres;
  std::vector<std::uint8_t> inBox;
  prepareTetrahedra(team, curve.xyz.data(), mesh, cells.box, centres, inBox);
  const Stars stars = starsOf(team, mesh, inBox, count + kFarPoints);
  std::vector<std::uint32_t> vertices, clipped; // the generators as the mesh numbers them
  for (std::uint32_t v = 0; v < count; ++v)
    if (mesh.representative[v] == v && curve.inputId[v] < options.generators)
    {
      if (stars.clipped[v])
        clipped.push_back(static_cast<std::uint32_t>(vertices.size()));
      vertices.push_back(v);
    }
  cells.generators.resize(vertices.size());
  for (std::size_t c = 0; c < vertices.size(); ++c)
    cells.generators[c] = curve.inputId[vertices[c]];
  if (options.density)
  {
    cells.densities.resize(vertices.size());
    for (std::size_t c = 0; c < vertices.size(); ++c)
      cells.densities[c] = density[vertices[c]];
  }

  // The clipped cells first: their sizes are known once they are clipped.
  CellSources sources{
    curve.xyz.data(), curve.inputId, mesh.tetrahedra.data(), stars, inBox, cells.box};
  sources.centres = centres.data();
  // A builder per thread, kept for both passes.
  std::vector<std::unique_ptr<CellBuilder>> builders(team.size());
  auto builder = [&](std::size_t k) -> CellBuilder& {
    if (!builders[k])
      builders[k] = std::make_unique<CellBuilder>(sources, count + kFarPoints);
    return *builders[k];
  };
  std::vector<Stretch> parts(team.partsFor(clipped.size()));
  team.forRanges(clipped.size(), "voronoi clipped cells",
    [&](std::size_t k, std::size_t begin, std::size_t end) {
      CellBuilder& cell = builder(k);
      for (std::size_t i = begin; i < end; ++i)
      {
        const std::uint32_t p = vertices[clipped[i]];
        cell.trace(p);
        cell.emitClipped(p, clipped[i], parts[k]);
      }
    });
  const CellPlaces at = placeCells(vertices, stars, parts, cells);
  IdArray pointOf(mesh.numberOfTetrahedra());
  placeCentres(team, vertices, sources, at, centres, pointOf, cells);
  Doubles().swap(centres);

  // The whole cells, straight into their places, then the clipped ones.
  sources.centres = nullptr;
  sources.pointOf = pointOf.data();
  sources.points = cells.points.data();
  team.forRanges(
    vertices.size(), "voronoi cells", [&](std::size_t k, std::size_t begin, std::size_t end) {
      CellBuilder& cell = builder(k);
      for (std::size_t c = begin; c < end; ++c)
      {
        const std::uint32_t p = vertices[c];
        if (stars.clipped[p])
          continue;
        cell.trace(p);
        cell.emitWhole(p, c, cells.cellFaces[c], at.vertex[c], cells);
      }
    });
  copyClipped(team, parts, at, pointOf, cells);
  cells.threadedWork = std::move(mesh.threadedWork);
  cells.threadedWork.insert(cells.threadedWork.end(), team.records().begin(), team.records().end());
  return cells;
}

} // namespace fd3
