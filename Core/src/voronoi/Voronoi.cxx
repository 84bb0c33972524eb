// Voronoi cells clipped to a box, from the exact Delaunay tetrahedralization.
//
// 1. The points are copied along a Hilbert curve, and eight far points, the corners of a cube
//    around the points and the box, join them: then every generator lies inside the hull, so its
//    cell is bounded and every ring of tetrahedra about one of its edges is closed. A box point x
//    is never nearer a far point f than its own generator p: |x - p| <= D, the diagonal of the
//    points and box together, while the corners lie at least 2 sqrt(3) D - D/2 > D from x. So
//    each cell's part inside the box is unchanged, and every face with a far point lies outside
//    the box.
// 2. Each tetrahedron's vertices are put in ascending order (orientation kept), and the
//    tetrahedra are grouped by their lowest vertex, each group ordered by the other three: an
//    order that the points alone decide (the mesh's own varies with the thread count). A
//    tetrahedron's circumcentre is computed once, from its vertices in that order (in
//    double-double where it is flat); a group's centres in the box are its cell's own, numbered
//    in the groups' order.
// 3. The stars: a vertex's own group, then the tetrahedra of lower vertices' groups that hold it,
//    listed in two passes (a count, then the ids), each thread keeping the vertices of its own
//    range; beside them, whether any centre of its star lies outside the box.
// 4. A cell's faces, per generator p: the ring of its star's tetrahedra about each edge (p, q),
//    turning counter-clockwise about p -> q, so the face is counter-clockwise seen from outside.
//    The faces go in the order the star meets their q, each ring from the last of the star's
//    tetrahedra in it: both follow from the star's order, the points' alone, so the cells do not
//    depend on the thread count or on how the generators are split among the threads.
// 5. The cells that leave the box first, on the threads: clipped by the box's six planes, each
//    face keeps its inside part, a crossing of an edge is computed from its two ends taken in
//    lexicographic order and put exactly on the plane (so the cells around that edge compute the
//    same point), and the crossings close a new face on the plane. With their sizes known (a
//    whole cell with a star of n tetrahedra has 2 + n/2 faces and 3n face vertices), every cell
//    has its place in the output: the centres each cell owns are numbered there, and the whole
//    cells are written straight into their places. Volume and surface area come from each face's
//    Newell vector. Without polyhedra (VoronoiOptions::polyhedra), the cells are traced and
//    clipped alike, but only their faces' neighbours, volumes and areas are written.
#include "fd3/Voronoi.h"

#include "Geometry.h"
#include "exact/DoubleDouble.h"
#include "exact/Predicates.h"
#include "fd3/Distributed.h"
#include "fd3/Measures.h"
#include "insertion/InsertionOrder.h"
#include "system/Platform.h"
#include "system/Threads.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <optional>
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

/// The rings of a positive tetrahedron about its edges from vertex g: about g -> `about`, a ring
/// turning counter-clockwise enters through the face with vertex `from` and leaves through the
/// face with `to`, where (g, about, from, to) is an even permutation.
struct RingTurn
{
  int about = 0, from = 0, to = 0;
};
struct RingTurns
{
  RingTurn turns[4][3] = {};
};

constexpr RingTurns makeRingTurns()
{
  RingTurns table;
  for (int g = 0; g < 4; ++g)
  {
    int n = 0;
    for (int about = 0; about < 4; ++about)
    {
      if (about == g)
        continue;
      int k = 0;
      while (k == g || k == about)
        ++k;
      const int l = 6 - g - about - k;
      const int order[4] = {g, about, k, l};
      int inversions = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          inversions += order[a] > order[b];
      const bool even = inversions % 2 == 0;
      table.turns[g][n++] = {about, even ? k : l, even ? l : k};
    }
  }
  return table;
}
constexpr RingTurns kRingTurns = makeRingTurns();
/// One byte per tetrahedron or vertex, written by the threads that own them (no zero fill first).
using Flags = std::vector<std::uint8_t, BulkAllocator<std::uint8_t>>;

/// The local indices of a tetrahedron's vertices but one.
constexpr int kOthers[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

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

/// Every vertex's star, from the tetrahedra grouped by their lowest vertex (the group's owner):
/// v's star is its own group and the tetrahedra of lower vertices' groups that hold it.
struct Stars
{
  /// 4 vertices each, in sortVertices' order; vertex v's group is [ownStart[v], ownStart[v + 1]),
  /// ordered by the tetrahedra's other three vertices, an order the points alone decide.
  IdArray tetrahedra;
  VoronoiCells::Offsets ownStart;
  /// The tetrahedra that hold v but not as their lowest vertex, in the groups' order:
  /// others[otherStart[v], otherStart[v + 1]).
  IdArray others;
  VoronoiCells::Offsets otherStart;
  /// Whether a tetrahedron of the vertex's star has its centre outside the box: its cell is
  /// clipped.
  Flags clipped;

  std::size_t sizeOf(std::uint32_t v) const
  {
    return ownStart[v + 1] - ownStart[v] + otherStart[v + 1] - otherStart[v];
  }
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

/// A face's Newell vector, summed over its edges as its corners come (each from the generator),
/// then its share of the cell's volume (six times: the vector dotted with a corner) and area
/// (twice: the vector's length).
class NewellSum
{
public:
  void add(const double* corner)
  {
    if (corners_++ == 0)
      std::copy_n(corner, 3, first_);
    addEdge(last_, corner);
    std::copy_n(corner, 3, last_);
  }
  void close(double& sixVolume, double& twiceArea)
  {
    addEdge(last_, first_);
    sixVolume += n_[0] * first_[0] + n_[1] * first_[1] + n_[2] * first_[2];
    twiceArea += std::sqrt(n_[0] * n_[0] + n_[1] * n_[1] + n_[2] * n_[2]);
  }

private:
  void addEdge(const double* a, const double* b)
  {
    n_[0] += a[1] * b[2] - a[2] * b[1];
    n_[1] += a[2] * b[0] - a[0] * b[2];
    n_[2] += a[0] * b[1] - a[1] * b[0];
  }
  double n_[3] = {0, 0, 0}, first_[3] = {0, 0, 0}, last_[3] = {0, 0, 0};
  std::size_t corners_ = 0;
};

/// What every cell is built from, shared by the threads (read only while cells are built).
struct CellSources
{
  const double* xyz;      ///< the points, along the curve
  const IdArray& inputId; ///< of each point but the far ones
  const Stars& stars;
  const std::array<double, 6>& box;
  bool polyhedra; ///< VoronoiOptions::polyhedra
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

  /// The faces of p's cell before any clipping, as ring steps: the ring of its star's tetrahedra
  /// about each edge (p, q), turning counter-clockwise about p -> q, so that the face is
  /// counter-clockwise seen from outside. The link vertices q are numbered as the star meets them;
  /// the star's order is the points' alone (Stars), and so are these numbers, the order of the
  /// faces (by them) and where each ring starts (at the last of the star's tetrahedra in it).
  void trace(std::uint32_t p)
  {
    const std::size_t size = in_.stars.sizeOf(p);
    links_ = 2 + size / 2; // the link is a sphere
    met_ = 0;
    link_.resize(links_ + 3); // room for a tetrahedron's three before they are counted
    firstFrom_.resize(links_);
    star_.resize(size);
    ++stamp_;
    if (links_ <= kDenseLinks)
    {
      if (steps_.size() < links_ * links_)
        steps_.resize(links_ * links_, {0, 0, 0});
      RingStep* steps = steps_.data();
      addStar(
        p, [this](std::uint32_t v) { return denseLinkIndex(v); },
        [steps](std::uint64_t key) -> RingStep& { return steps[key]; });
      for (std::size_t i = 0; i < met_; ++i)
        linkOf_[link_[i]] = kNoLink;
    }
    else
    {
      linkOfLarge_.clear();
      stepsLarge_.clear();
      addStar(
        p, [this](std::uint32_t v) { return largeLinkIndex(v); },
        [this](std::uint64_t key) -> RingStep& { return stepsLarge_[key]; });
    }
    if (met_ != links_)
      throw std::logic_error("voronoiCells: a generator's link is not a sphere");
    link_.resize(links_);
  }

  /// A cell inside the box, written where `at` says: its faces are the rings as they are, each
  /// traced straight into the output (the volume's and area's sums beside the ring's steps, which
  /// wait on each other).
  template <bool Polyhedra>
  void emitWhole(
    std::uint32_t p, std::size_t cell, std::size_t face, std::size_t vertex, VoronoiCells& out)
  {
    const std::size_t links = link_.size(), longest = star_.size();
    const double* g = in_.xyz + 3 * std::size_t(p);
    fromGenerator_.resize(longest);
    if constexpr (Polyhedra)
      pointOf_.resize(longest);
    for (std::size_t i = 0; i < longest; ++i)
    {
      const double* x;
      if constexpr (Polyhedra)
      {
        pointOf_[i] = in_.pointOf[star_[i]];
        x = in_.points + 3 * std::size_t(pointOf_[i]);
      }
      else
        x = in_.centres + 3 * std::size_t(star_[i]);
      fromGenerator_[i] = {x[0] - g[0], x[1] - g[1], x[2] - g[2]};
    }
    const std::size_t end = vertex + 3 * longest;
    const RingStep* steps = links <= kDenseLinks ? steps_.data() : nullptr;
    const std::array<double, 3>* corner = fromGenerator_.data();
    const std::uint32_t stamp = stamp_;
    double sixVolume = 0, twiceArea = 0;
    out.cellFaces[cell] = face;
    for (std::uint32_t q = 0; q < links; ++q, ++face)
    {
      if constexpr (Polyhedra)
        out.faceStart[face] = vertex;
      out.faceNeighbors[face] = inputId(link_[q]);
      // The Newell sums spelled out: through NewellSum this loop ran markedly slower.
      const std::uint64_t first = std::uint64_t(q) * links + firstFrom_[q];
      std::uint64_t key = first;
      const std::size_t begin = vertex;
      double n[3] = {0, 0, 0}, a[3] = {0, 0, 0}, a0[3] = {0, 0, 0};
      do
      {
        const RingStep& next = steps ? steps[key] : stepAt(key);
        if (next.cell != stamp || vertex == end)
          throw std::logic_error("voronoiCells: a ring about an edge is open");
        const std::uint32_t star = next.star;
        if constexpr (Polyhedra)
          out.faceVertices[vertex] = pointOf_[star];
        const double* b = corner[star].data();
        if (vertex == begin)
          std::copy_n(b, 3, a0);
        n[0] += a[1] * b[2] - a[2] * b[1];
        n[1] += a[2] * b[0] - a[0] * b[2];
        n[2] += a[0] * b[1] - a[1] * b[0];
        std::copy_n(b, 3, a);
        ++vertex;
        key = next.next;
      } while (key != first);
      n[0] += a[1] * a0[2] - a[2] * a0[1];
      n[1] += a[2] * a0[0] - a[0] * a0[2];
      n[2] += a[0] * a0[1] - a[1] * a0[0];
      sixVolume += n[0] * a0[0] + n[1] * a0[1] + n[2] * a0[2];
      twiceArea += std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    if (vertex != end)
      throw std::logic_error("voronoiCells: a generator's link is not a sphere");
    out.volumes[cell] = sixVolume / 6;
    out.areas[cell] = twiceArea / 2;
  }

  /// A cell that leaves the box, clipped by its six planes, into `out`.
  void emitClipped(std::uint32_t p, std::uint32_t cell, Stretch& out)
  {
    // The centres, scattered over the tetrahedra's order, are loaded while the rings are traced
    // rather than one cache miss after the other as the polyhedron is made.
    for (const std::uint32_t t : star_)
      prefetch(centre(t));
    traceRings();
    makePolyhedron();
    for (int wall = 0; wall < 6 && !cell_.neighbors.empty(); ++wall)
      clip(wall);
    const Polyhedron& c = cell_;
    const std::size_t faces = c.neighbors.size();
    out.cells.push_back(cell);
    out.faceCounts.push_back(static_cast<std::uint32_t>(faces));
    crossingOf_.assign(c.x.size(), kNone);
    const double* g = in_.xyz + 3 * std::size_t(p);
    double sixVolume = 0, twiceArea = 0;
    std::uint32_t crossings = 0;
    for (std::size_t f = 0; f < faces; ++f)
    {
      const std::uint32_t begin = c.faceStart[f], size = c.faceStart[f + 1] - begin;
      out.faceSizes.push_back(size);
      out.neighbors.push_back(inputId(c.neighbors[f]));
      for (std::uint32_t k = 0; k < size && in_.polyhedra; ++k)
      {
        const std::uint32_t v = c.loops[begin + k], t = c.tet[v];
        if (t != kNone)
        {
          out.vertices.push_back(t);
          continue;
        }
        if (crossingOf_[v] == kNone)
        {
          crossingOf_[v] = crossings++;
          out.crossingPoints.insert(out.crossingPoints.end(), c.x[v].begin(), c.x[v].end());
        }
        out.vertices.push_back(kOwnVertex | crossingOf_[v]);
      }
      NewellSum newell;
      for (std::uint32_t k = 0; k < size; ++k)
      {
        const std::array<double, 3>& x = c.x[c.loops[begin + k]];
        const double corner[3] = {x[0] - g[0], x[1] - g[1], x[2] - g[2]};
        newell.add(corner);
      }
      newell.close(sixVolume, twiceArea);
    }
    out.crossings.push_back(crossings);
    out.volumes.push_back(sixVolume / 6);
    out.areas.push_back(twiceArea / 2);
  }

private:
  /// A tetrahedron's step in the ring about (p, q), kept under the key of (q, the link vertex of
  /// the face it enters by): `next` is the key of the step after it, `star` the tetrahedron's
  /// index in the star, `cell` the cell that wrote it.
  struct RingStep
  {
    std::uint64_t next;
    std::uint32_t star, cell;
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

  /// The star's tetrahedra into star_, their link vertices numbered by linkIndex(v), and each
  /// one's steps in the rings about its three link vertices, through step(key).
  template <typename LinkIndex, typename Step>
  void addStar(std::uint32_t p, LinkIndex linkIndex, Step step)
  {
    const Stars& stars = in_.stars;
    const std::uint32_t* t4 = stars.tetrahedra.data();
    const std::uint64_t links = links_;
    std::uint32_t i = 0;
    auto add = [&](std::uint32_t t, int generator) {
      const std::uint32_t* v = t4 + 4 * std::size_t(t);
      std::uint32_t link[4] = {0, 0, 0, 0};
      for (const int k : kOthers[generator])
        link[k] = linkIndex(v[k]);
      if (met_ > links_)
        throw std::logic_error("voronoiCells: a generator's link is not a sphere");
      for (const RingTurn& turn : kRingTurns.turns[generator])
      {
        const std::uint32_t q = link[turn.about], from = link[turn.from];
        step(q * links + from) = {q * links + link[turn.to], i, stamp_};
        firstFrom_[q] = from;
      }
      star_[i++] = t;
    };
    for (std::size_t t = stars.ownStart[p]; t < stars.ownStart[p + 1]; ++t)
      add(static_cast<std::uint32_t>(t), 0);
    // The others lie in the groups of lower vertices, some long left behind: fetched ahead.
    const std::size_t first = stars.otherStart[p], last = stars.otherStart[p + 1];
    for (std::size_t k = first; k < last && k < first + kAhead; ++k)
      prefetch(t4 + 4 * std::size_t(stars.others[k]));
    for (std::size_t k = first; k < last; ++k)
    {
      if (k + kAhead < last)
        prefetch(t4 + 4 * std::size_t(stars.others[k + kAhead]));
      const std::uint32_t t = stars.others[k];
      add(t, localIndex(t4 + 4 * std::size_t(t), p));
    }
  }

  /// v's index in link_, which it joins if new (without a branch: new or not is a coin toss).
  std::uint32_t denseLinkIndex(std::uint32_t v)
  {
    std::uint16_t& index = linkOf_[v];
    link_[met_] = v;
    const bool added = index == kNoLink;
    index = added ? static_cast<std::uint16_t>(met_) : index;
    met_ += added;
    return index;
  }

  std::uint32_t largeLinkIndex(std::uint32_t v)
  {
    const auto found = linkOfLarge_.emplace(v, static_cast<std::uint32_t>(met_));
    if (found.second)
      link_[met_++] = v;
    return found.first->second;
  }

  const RingStep& stepAt(std::uint64_t key) const
  {
    static const RingStep none = {0, 0, 0}; // of no cell: stamps start at 1
    if (link_.size() <= kDenseLinks)
      return steps_[key];
    const auto found = stepsLarge_.find(key);
    return found == stepsLarge_.end() ? none : found->second;
  }

  /// The rings, into loops_ / faceStart_: face q's is the ring about link_[q].
  void traceRings()
  {
    const std::size_t links = link_.size();
    loops_.clear();
    faceStart_.resize(links + 1);
    faceStart_[0] = 0;
    for (std::uint32_t q = 0; q < links; ++q)
    {
      const std::uint64_t first = std::uint64_t(q) * links + firstFrom_[q];
      std::uint64_t key = first;
      const std::size_t begin = loops_.size();
      do
      {
        const RingStep& step = stepAt(key);
        if (step.cell != stamp_ || loops_.size() - begin == star_.size())
          throw std::logic_error("voronoiCells: a ring about an edge is open");
        loops_.push_back(step.star);
        key = step.next;
      } while (key != first);
      faceStart_[q + 1] = static_cast<std::uint32_t>(loops_.size());
    }
  }

  void makePolyhedron()
  {
    Polyhedron& c = cell_;
    c.x.clear();
    c.tet.clear();
    c.loops.clear();
    c.faceStart.assign(1, 0);
    c.neighbors.clear();
    localOf_.assign(star_.size(), kNone);
    for (std::size_t f = 0; f + 1 < faceStart_.size(); ++f)
    {
      for (std::uint32_t k = faceStart_[f]; k < faceStart_[f + 1]; ++k)
      {
        std::uint32_t& v = localOf_[loops_[k]];
        if (v == kNone)
        {
          const std::uint32_t t = star_[loops_[k]];
          v = static_cast<std::uint32_t>(c.x.size());
          const double* x = centre(t);
          c.x.push_back({x[0], x[1], x[2]});
          c.tet.push_back(t);
        }
        c.loops.push_back(v);
      }
      c.faceStart.push_back(static_cast<std::uint32_t>(c.loops.size()));
      c.neighbors.push_back(link_[f]);
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
    std::vector<std::uint32_t>& loops = keptLoops_;
    std::vector<std::uint32_t>& faceStart = keptStarts_;
    std::vector<std::uint32_t>& neighbors = keptNeighbors_;
    loops.clear();
    faceStart.assign(1, 0);
    neighbors.clear();
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

  /// Links of up to this many vertices are numbered in linkOf_ and have their ring steps in a
  /// square table.
  static constexpr std::size_t kDenseLinks = 256;
  /// How far ahead in a star's list its tetrahedra are fetched.
  static constexpr std::size_t kAhead = 8;
  static constexpr std::uint16_t kNoLink = 0xFFFF;

  const CellSources& in_;
  // One cell's scratch, kept between cells for its memory.
  std::vector<std::uint32_t> star_; ///< the tetrahedra around the generator
  std::vector<std::uint32_t> link_; ///< the vertices joined to the generator, as met
  /// Each vertex's index in link_ while a cell is traced (kNoLink otherwise): two bytes a vertex
  /// per thread, against a hash map's several lookups.
  std::vector<std::uint16_t> linkOf_;
  std::unordered_map<std::uint32_t, std::uint32_t> linkOfLarge_;
  std::vector<RingStep> steps_; ///< links x links, by (q, from)
  std::unordered_map<std::uint64_t, RingStep> stepsLarge_;
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> firstFrom_; ///< per link vertex: where its ring starts
  std::size_t links_ = 0; ///< the link's vertices: 2 + n/2 for a star of n tetrahedra
  std::size_t met_ = 0;   ///< the link's vertices met so far
  /// A clipped cell's local vertex of each star tetrahedron, and its crossing of each local
  /// vertex (kNone where it has none yet).
  std::vector<std::uint32_t> localOf_, crossingOf_;
  /// The faces a clip keeps, swapped into cell_.
  std::vector<std::uint32_t> keptLoops_, keptStarts_, keptNeighbors_;
  std::vector<std::uint32_t> loops_, faceStart_;
  std::vector<std::array<double, 3>> fromGenerator_; ///< per star tetrahedron: its centre - p
  std::vector<std::uint32_t> pointOf_;               ///< per star tetrahedron: its centre's point
  Polyhedron cell_;
  std::vector<std::array<std::uint32_t, 3>> crossings_;
  std::vector<std::pair<std::uint32_t, bool>> events_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> capEdges_;
  std::vector<bool> capUsed_;
};

/// The bounding box of the finite points, in VTK's order; false when there is none.
bool finiteBounds(
  ThreadTeam& team, const double* xyz, std::size_t count, std::array<double, 6>& bounds)
{
  std::vector<std::optional<Box>> boxes(team.partsFor(count)); // each stretch's
  team.forRanges(count, "voronoi curve", [&](std::size_t k, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      if (isFinite(xyz + 3 * i))
      {
        if (boxes[k])
          boxes[k]->include(xyz + 3 * i);
        else
          boxes[k] = Box::around(xyz + 3 * i);
      }
  });
  std::optional<Box> box;
  for (const std::optional<Box>& b : boxes)
    if (b && box)
    {
      box->include(b->lo);
      box->include(b->hi);
    }
    else if (b)
      box = b;
  if (box)
    bounds = {box->lo[0], box->hi[0], box->lo[1], box->hi[1], box->lo[2], box->hi[2]};
  return box.has_value();
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
  VoronoiCells::Doubles xyz; ///< empty when the corners are not finite
  IdArray inputId;           ///< of each point but the corners
};

CurvePoints alongCurve(ThreadTeam& team, const double* xyz, std::size_t count,
  std::size_t generators, const std::array<double, 6>& points, const std::array<double, 6>& box)
{
  const double cells = double(1u << kHilbertBits);
  double scale[3];
  for (int a = 0; a < 3; ++a)
  {
    const double extent = points[2 * a + 1] - points[2 * a];
    scale[a] = extent > 0 && std::isfinite(extent) ? cells / extent : 0;
  }
  const std::vector<double> far = voronoiFarPoints(points, box);
  if (far.empty())
    return {};
  CurvePoints curve;
  curve.xyz.resize(3 * (count + kFarPoints));
  std::copy(far.begin(), far.end(), curve.xyz.begin() + std::ptrdiff_t(3 * count));
  Words keys(count); // position along the curve << 32 | id
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* p = xyz + 3 * i;
      // Not finite: after every finite point.
      std::uint64_t position = std::uint64_t(1) << (3 * kHilbertBits + 1);
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
      keys[i] = position << 32 | i;
    }
  });
  radixSortByHighHalf(keys, 3 * kHilbertBits + 2, &team);
  curve.inputId.resize(count);
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const auto id = static_cast<std::uint32_t>(keys[k]);
      curve.inputId[k] = id;
      for (int a = 0; a < 3; ++a)
        curve.xyz[3 * k + a] = xyz[3 * std::size_t(id) + a];
    }
  });
  team.release(keys, "voronoi curve");
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
  // The volume's rounding in double-double is a few 2^-106 of the edges' product; below
  // kTrustedFlatness of that product the offset would keep fewer than about 12 digits (three
  // points of a speck far smaller than its distance to the fourth): computed exactly instead.
  constexpr double kTrustedFlatness = 1e-18;
  const double edgeProduct = std::sqrt(uu.value() * vv.value() * ww.value());
  if (!(std::fabs(twiceVolume) > 2 * kTrustedFlatness * edgeProduct))
  {
    const double* p[4] = {&xyz[3 * std::size_t(ids[0])], &xyz[3 * std::size_t(ids[1])],
      &xyz[3 * std::size_t(ids[2])], &xyz[3 * std::size_t(ids[3])]};
    exactCircumcentreOffset(p[0], p[1], p[2], p[3], offset);
    return;
  }
  for (int k = 0; k < 3; ++k)
    offset[k] = (uu * vw[k] + vv * wu[k] + ww * uv[k]).value() / twiceVolume * up;
}

/// ilogb(x) for a finite x > 0, read from its bits where it is normal.
int binaryExponent(double x)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>(bits >> 52);
  return biased > 0 ? biased - 1023 : std::ilogb(x);
}

/// 2^e for -1022 <= e <= 1023, built from its bits.
double powerOfTwo(int e)
{
  const std::uint64_t bits = std::uint64_t(1023 + e) << 52;
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
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
  const int exponent = binaryExponent(longest);
  const bool normal = exponent > -1000 && exponent < 1000; // 2^-exponent is a double
  const double down = normal ? powerOfTwo(-exponent) : 0, up = normal ? powerOfTwo(exponent) : 0;
  for (auto& edge : edges)
    for (double& x : edge)
      x = normal ? x * down : std::ldexp(x, -exponent);
  const Circumcentre c = circumcentreOfEdges(edges[0], edges[1], edges[2]);
  double offset[3];
  for (int k = 0; k < 3; ++k)
    offset[k] = normal ? c.offset[k] * up : std::ldexp(c.offset[k], exponent);
  if (normal && c.sixVolume * c.sixVolume < kFlat * kFlat * c.edgeProduct2)
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
/// odd permutation of the mesh's, so that it stays positively oriented. The mesh's rotation of
/// the vertices varies with the thread count; this order, the centres' rounding and everything
/// built from them depend on the points alone.
void sortVertices(ThreadTeam& team, Triangulation& mesh)
{
  std::uint32_t* t4 = mesh.tetrahedra.data();
  team.forRanges(mesh.numberOfTetrahedra(), "voronoi vertex order",
    [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
      {
        std::uint32_t* v = t4 + 4 * t;
        // A sorting network of five exchanges; each exchange flips the orientation.
        // Without branches: each exchange is a coin toss.
        bool odd = false;
        auto exchange = [&](int i, int j) {
          const std::uint32_t a = v[i], b = v[j];
          const bool swap = b < a;
          v[i] = swap ? b : a;
          v[j] = swap ? a : b;
          odd ^= swap;
        };
        exchange(0, 1);
        exchange(2, 3);
        exchange(0, 2);
        exchange(1, 3);
        exchange(1, 2);
        const std::uint32_t third = v[2], fourth = v[3];
        v[2] = odd ? fourth : third;
        v[3] = odd ? third : fourth;
      }
    });
}

/// Whether tetrahedron a's other three vertices come before b's, lexicographically.
bool otherVerticesLess(const std::uint32_t* a, const std::uint32_t* b)
{
  return a[1] != b[1] ? a[1] < b[1] : (a[2] != b[2] ? a[2] < b[2] : a[3] < b[3]);
}

/// Sorts a group's tetrahedra by their other three vertices: by insertion where it is small, as
/// nearly every group is, else through an index.
void sortGroup(std::uint32_t* first, std::size_t size, std::vector<std::uint32_t>& scratch)
{
  using Tet = std::array<std::uint32_t, 4>;
  constexpr std::size_t kInsertion = 32;
  if (size <= kInsertion)
  {
    for (std::size_t i = 1; i < size; ++i)
    {
      Tet moving;
      std::copy_n(first + 4 * i, 4, moving.begin());
      std::size_t j = i;
      for (; j > 0 && otherVerticesLess(moving.data(), first + 4 * (j - 1)); --j)
        std::copy_n(first + 4 * (j - 1), 4, first + 4 * j);
      std::copy_n(moving.begin(), 4, first + 4 * j);
    }
    return;
  }
  std::vector<Tet> tets(size);
  for (std::size_t i = 0; i < size; ++i)
    std::copy_n(first + 4 * i, 4, tets[i].begin());
  std::sort(tets.begin(), tets.end(),
    [](const Tet& a, const Tet& b) { return otherVerticesLess(a.data(), b.data()); });
  scratch.assign(&tets[0][0], &tets[0][0] + 4 * size);
  std::copy(scratch.begin(), scratch.end(), first);
}

/// The mesh's tetrahedra grouped by their lowest vertex into stars.tetrahedra (the mesh's array
/// goes to stars.others), and each vertex's other tetrahedra counted. Each thread scans every tetrahedron
/// for the vertices of its own range, so that no two threads write one vertex's entries.
void groupByLowestVertex(ThreadTeam& team, Triangulation& mesh, std::size_t vertices, Stars& stars)
{
  const std::size_t tets = mesh.numberOfTetrahedra();
  const std::uint32_t* t4 = mesh.tetrahedra.data();
  stars.ownStart.resize(vertices + 1);
  stars.otherStart.resize(vertices + 1);
  stars.ownStart[0] = stars.otherStart[0] = 0;
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::fill(&stars.ownStart[lo + 1], &stars.ownStart[hi] + 1, 0);
    std::fill(&stars.otherStart[lo + 1], &stars.otherStart[hi] + 1, 0);
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      // Branches, not sums of flags: a thread must not write another's entries, even unchanged.
      if (v[0] >= lo && v[0] < hi)
        ++stars.ownStart[v[0] + 1];
      for (int k = 1; k < 4; ++k)
        if (v[k] >= lo && v[k] < hi)
          ++stars.otherStart[v[k] + 1];
    }
  });
  team.accumulate(stars.ownStart, "voronoi stars");
  team.accumulate(stars.otherStart, "voronoi stars");
  stars.tetrahedra.resize(4 * tets);
  VoronoiCells::Offsets next(vertices); // where each group's next tetrahedron goes
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::copy(&stars.ownStart[lo], &stars.ownStart[hi], &next[lo]);
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      if (v[0] >= lo && v[0] < hi)
        std::copy_n(v, 4, stars.tetrahedra.data() + 4 * next[v[0]]++);
    }
  });
  // The mesh's array (4 entries a tetrahedron) is the room for the others' list (3 a
  // tetrahedron), in pages already the process's.
  stars.others.swap(mesh.tetrahedra);
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::vector<std::uint32_t> scratch;
    for (std::size_t v = lo; v < hi; ++v)
      sortGroup(stars.tetrahedra.data() + 4 * stars.ownStart[v],
        stars.ownStart[v + 1] - stars.ownStart[v], scratch);
  });
}

/// Each tetrahedron's circumcentre, from its vertices in their order (in double-double where it
/// is flat), and whether it lies in the closed box.
void circumcentres(ThreadTeam& team, const double* xyz, const IdArray& tetrahedra,
  const std::array<double, 6>& box, Doubles& centres, Flags& inBox)
{
  const std::size_t tets = tetrahedra.size() / 4;
  centres.resize(3 * tets);
  inBox.resize(tets);
  team.forRanges(tets, "circumcentres", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      const std::uint32_t* v = tetrahedra.data() + 4 * t;
      double* x = &centres[3 * t];
      for (int a = 0; a < 3; ++a)
        x[a] = xyz[3 * std::size_t(v[0]) + a];
      addScaledCircumcentre(xyz, v, x);
      inBox[t] = x[0] >= box[0] && x[0] <= box[1] && x[1] >= box[2] && x[1] <= box[3] &&
        x[2] >= box[4] && x[2] <= box[5];
    }
  });
}

/// Each vertex's other tetrahedra (those of lower vertices' groups that hold it), and whether
/// its cell is clipped.
void listOthers(ThreadTeam& team, const Flags& inBox, Stars& stars)
{
  const std::size_t tets = inBox.size(), vertices = stars.ownStart.size() - 1;
  const std::uint32_t* t4 = stars.tetrahedra.data();
  stars.others.resize(stars.otherStart[vertices]);
  stars.clipped.resize(vertices);
  VoronoiCells::Offsets next(vertices); // where each vertex's next other tetrahedron goes
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::copy(&stars.otherStart[lo], &stars.otherStart[hi], &next[lo]);
    std::fill(&stars.clipped[lo], &stars.clipped[hi], 0);
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      if (v[0] >= lo && v[0] < hi)
        stars.clipped[v[0]] |= !inBox[t];
      for (int k = 1; k < 4; ++k)
        if (v[k] >= lo && v[k] < hi)
        {
          stars.others[next[v[k]]++] = static_cast<std::uint32_t>(t);
          stars.clipped[v[k]] |= !inBox[t];
        }
    }
  });
}

/// The output point of each centre in the box, numbered in the tetrahedra's order: the centres
/// of each group, the ones its cell owns, follow each other, cell after cell. One entry more
/// than the tetrahedra: the count of centres before each one, and in all.
IdArray numberCentres(ThreadTeam& team, const Flags& inBox)
{
  const std::size_t tets = inBox.size();
  IdArray pointOf(tets + 1);
  std::size_t points = 0;
  team.countThenWrite(
    team.newRecord("voronoi centres"), 0, tets, points,
    [&](std::size_t begin, std::size_t end) {
      return std::size_t(std::count(inBox.begin() + std::ptrdiff_t(begin),
        inBox.begin() + std::ptrdiff_t(end), std::uint8_t(1)));
    },
    [&](std::size_t, std::size_t begin, std::size_t end, std::size_t point) {
      for (std::size_t t = begin; t < end; ++t)
      {
        pointOf[t] = static_cast<std::uint32_t>(point);
        point += inBox[t];
      }
      return point;
    });
  pointOf[tets] = static_cast<std::uint32_t>(points);
  return pointOf;
}

/// The generators as the mesh numbers them (the points of the first `generators` ids that are
/// vertices, not merged into another), ascending, and the indices among them of the clipped
/// cells.
void listGenerators(ThreadTeam& team, const Triangulation& mesh, const IdArray& inputId,
  std::size_t generators, const Stars& stars, IdArray& vertices, IdArray& clipped)
{
  ThreadedWork& record = team.newRecord("voronoi generators");
  vertices = team.indicesWhere(record, 0, inputId.size(),
    [&](std::size_t v) { return mesh.representative[v] == v && inputId[v] < generators; });
  clipped = team.indicesWhere(
    record, 0, vertices.size(), [&](std::size_t c) { return stars.clipped[vertices[c]] != 0; });
}

/// Where each cell's parts go in the output: its first face vertex and crossing (its first face
/// is cellFaces', its centres are numbered by numberCentres).
struct CellPlaces
{
  VoronoiCells::Offsets vertex, crossing;
};

/// The sizes of the cells (those of the clipped ones from their stretches; a whole cell with a
/// star of n tetrahedra has 2 + n/2 faces, those of its link, a sphere, and 3n face vertices),
/// summed into places, and the output's arrays made to hold them.
CellPlaces placeCells(ThreadTeam& team, const IdArray& vertices, const Stars& stars,
  const IdArray& pointOf, const std::vector<Stretch>& parts, VoronoiCells& cells)
{
  const std::size_t n = vertices.size();
  CellPlaces at;
  at.vertex.resize(n + 1);
  at.crossing.resize(n + 1);
  cells.cellFaces.resize(n + 1);
  // Each cell's sizes after its place, then their running sums. The crossings are numbered after
  // the centres that the cells own.
  cells.cellFaces[0] = at.vertex[0] = 0;
  at.crossing[0] = n && !pointOf.empty() ? pointOf[stars.ownStart[vertices[n - 1] + 1]] : 0;
  team.forRanges(n, "voronoi places", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
      if (const std::uint32_t p = vertices[c]; !stars.clipped[p])
      {
        const std::size_t star = stars.sizeOf(p);
        cells.cellFaces[c + 1] = 2 + star / 2;
        at.vertex[c + 1] = 3 * star;
        at.crossing[c + 1] = 0;
      }
  });
  team.run(
    parts.size(),
    [&](std::size_t k) {
      const Stretch& s = parts[k];
      auto face = s.faceSizes.begin();
      for (std::size_t j = 0; j < s.cells.size(); ++j)
      {
        const std::size_t c = s.cells[j];
        cells.cellFaces[c + 1] = s.faceCounts[j];
        at.vertex[c + 1] = std::accumulate(face, face + s.faceCounts[j], std::size_t(0));
        at.crossing[c + 1] = s.crossings[j];
        face += s.faceCounts[j];
      }
    },
    team.newRecord("voronoi places"));
  team.accumulate(cells.cellFaces, "voronoi places");
  team.accumulate(at.vertex, "voronoi places");
  team.accumulate(at.crossing, "voronoi places");
  cells.faceNeighbors.resize(cells.cellFaces[n]);
  cells.volumes.resize(n);
  cells.areas.resize(n);
  if (pointOf.empty()) // no polyhedra
  {
    cells.faceStart.clear();
    return at;
  }
  const std::size_t points = at.crossing[n];
  if (points >= kOwnVertex)
    throw std::length_error("voronoiCells: more than 2^31 vertices");
  cells.faceStart.resize(cells.cellFaces[n] + 1);
  cells.faceStart[cells.cellFaces[n]] = at.vertex[n];
  cells.faceVertices.resize(at.vertex[n]);
  cells.points.resize(3 * points);
  return at;
}

/// The centres in the box of the tetrahedra of the cells' groups into the output's points.
void copyCentres(ThreadTeam& team, std::size_t tets, const Flags& inBox, const IdArray& pointOf,
  const Doubles& centres, VoronoiCells& cells)
{
  team.forRanges(tets, "voronoi centres", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
      if (inBox[t])
        std::copy_n(&centres[3 * t], 3, &cells.points[3 * std::size_t(pointOf[t])]);
  });
}

/// The clipped cells' stretches into the output, their circumcentres numbered through pointOf
/// (empty without polyhedra).
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
          cells.faceNeighbors[outFace] = s.neighbors[face];
          if (pointOf.empty()) // no polyhedra
            continue;
          cells.faceStart[outFace] = outVertex;
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
/// The tetrahedra's vertices and the representatives of a mesh of points in their input order
/// (the far points last), in the curve's ids instead (inputId: the input id at each place).
void renumberAlongCurve(ThreadTeam& team, const IdArray& inputId, Triangulation& mesh)
{
  const std::size_t count = inputId.size();
  IdArray place(count + kFarPoints);
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
      place[inputId[k]] = static_cast<std::uint32_t>(k);
  });
  for (std::size_t k = count; k < count + kFarPoints; ++k)
    place[k] = static_cast<std::uint32_t>(k);
  std::uint32_t* t4 = mesh.tetrahedra.data();
  team.forRanges(
    mesh.tetrahedra.size(), "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        t4[i] = place[t4[i]];
    });
  IdArray representative(mesh.representative.size());
  team.forRanges(
    count + kFarPoints, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k)
      {
        const std::uint32_t id = k < count ? inputId[k] : static_cast<std::uint32_t>(k);
        const std::uint32_t r = mesh.representative[id];
        representative[k] = r == kNoPoint ? kNoPoint : place[r];
      }
    });
  mesh.representative.swap(representative);
}

/// The cells from the tetrahedralization of the points along the curve and the far points (in
/// the curve's ids), with each point's density in the curve's order where asked for.
VoronoiCells cellsOf(ThreadTeam& team, CurvePoints curve, std::size_t count,
  const VoronoiOptions& options, Triangulation mesh, const std::vector<double>& density,
  VoronoiCells cells)
{
  cells.stats = mesh.stats;
  cells.stats.inputPoints -= kFarPoints;
  cells.stats.insertedPoints -= kFarPoints;
  if (mesh.status != Status::Ok)
  {
    cells.status = mesh.status;
    return cells;
  }

  sortVertices(team, mesh);
  Stars stars;
  groupByLowestVertex(team, mesh, count + kFarPoints, stars);
  Doubles centres;
  Flags inBox;
  circumcentres(team, curve.xyz.data(), stars.tetrahedra, cells.box, centres, inBox);
  listOthers(team, inBox, stars);
  IdArray pointOf = options.polyhedra ? numberCentres(team, inBox) : IdArray();
  IdArray vertices, clipped;
  listGenerators(team, mesh, curve.inputId, options.generators, stars, vertices, clipped);
  cells.generators.resize(vertices.size());
  if (options.density)
    cells.densities.resize(vertices.size());
  team.forRanges(
    vertices.size(), "voronoi cells", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c)
      {
        cells.generators[c] = curve.inputId[vertices[c]];
        if (options.density)
          cells.densities[c] = density[vertices[c]];
      }
    });

  // The clipped cells first: their sizes are known once they are clipped.
  CellSources sources{curve.xyz.data(), curve.inputId, stars, cells.box, options.polyhedra};
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
  const CellPlaces at = placeCells(team, vertices, stars, pointOf, parts, cells);
  if (options.polyhedra)
  {
    if (!vertices.empty())
      copyCentres(team, stars.ownStart[vertices.back() + 1], inBox, pointOf, centres, cells);
    team.release(centres, "voronoi centres");
    sources.centres = nullptr;
    sources.pointOf = pointOf.data();
    sources.points = cells.points.data();
  }

  // The whole cells, straight into their places, then the clipped ones.
  team.forRanges(
    vertices.size(), "voronoi cells", [&](std::size_t k, std::size_t begin, std::size_t end) {
      CellBuilder& cell = builder(k);
      for (std::size_t c = begin; c < end; ++c)
      {
        const std::uint32_t p = vertices[c];
        if (stars.clipped[p])
          continue;
        cell.trace(p);
        if (options.polyhedra)
          cell.emitWhole<true>(p, c, cells.cellFaces[c], at.vertex[c], cells);
        else
          cell.emitWhole<false>(p, c, cells.cellFaces[c], at.vertex[c], cells);
      }
    });
  copyClipped(team, parts, at, pointOf, cells);
  // What the cells came from, its pages given back on every thread: on return, one thread would.
  team.release(centres, "voronoi release");
  team.release(pointOf, "voronoi release");
  team.release(stars.tetrahedra, "voronoi release");
  team.release(stars.others, "voronoi release");
  team.release(curve.xyz, "voronoi release");
  cells.threadedWork = std::move(mesh.threadedWork);
  const std::vector<ThreadedWork> records = team.records();
  cells.threadedWork.insert(cells.threadedWork.end(), records.begin(), records.end());
  return cells;
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
  ThreadTeam team(boundedThreads(options.threads));
  std::array<double, 6> bounds;
  if (!finiteBounds(team, xyz, count, bounds))
  {
    cells.status = Status::Empty;
    cells.stats.nonFinitePoints = count;
    return cells;
  }
  cells.box = isBox(options.box) ? options.box : bounds;
  CurvePoints curve = alongCurve(team, xyz, count, options.generators, bounds, cells.box);
  if (curve.xyz.empty())
  {
    cells.status = Status::OutOfRange;
    return cells;
  }

  std::vector<double> density;
  Triangulation mesh = meshOf(curve, count, options, density);
  return cellsOf(
    team, std::move(curve), count, options, std::move(mesh), density, std::move(cells));
}

VoronoiCells voronoiCells(IncrementalDelaunay& mesh, const std::array<double, 6>& pointBounds,
  const VoronoiOptions& options, Coordinates& xyz)
{
  VoronoiCells cells;
  cells.cellFaces.assign(1, 0);
  cells.faceStart.assign(1, 0);
  const Status before = mesh.status();
  if (before == Status::Empty || before == Status::Aborted) // no finite point, whatever the box
  {
    cells.stats = mesh.release(xyz).stats;
    cells.status = before;
    return cells;
  }
  if (!isBox(options.box))
    throw std::invalid_argument("fd3::voronoiCells: the clipping box of a mesh's cells is empty");
  cells.box = options.box;
  ThreadTeam team(boundedThreads(options.threads));
  const std::vector<double> far = voronoiFarPoints(pointBounds, cells.box);
  if (far.empty())
  {
    cells.stats = mesh.release(xyz).stats;
    cells.status = Status::OutOfRange;
    return cells;
  }
  // The densities come from the points' own tetrahedra, before the far points change those at
  // the hull.
  Triangulation own;
  if (options.density)
    own = mesh.snapshot();
  mesh.add(far.data(), kFarPoints);
  Triangulation tetrahedra = mesh.release(xyz);
  const std::size_t count = xyz.size() / 3 - kFarPoints;
  CurvePoints curve =
    alongCurve(team, xyz.data(), count, options.generators, pointBounds, cells.box);
  std::vector<double> density;
  if (options.density)
  {
    const std::vector<double> byPoint = densities(xyz.data(), count, own);
    own = Triangulation();
    density.resize(count);
    for (std::size_t k = 0; k < count; ++k)
      density[k] = byPoint[curve.inputId[k]];
  }
  xyz.resize(3 * count);
  renumberAlongCurve(team, curve.inputId, tetrahedra);
  return cellsOf(
    team, std::move(curve), count, options, std::move(tetrahedra), density, std::move(cells));
}

std::vector<double> voronoiFarPoints(
  const std::array<double, 6>& pointBounds, const std::array<double, 6>& box)
{
  double both[6], centre[3];
  for (int a = 0; a < 3; ++a)
  {
    both[2 * a] = std::min(pointBounds[2 * a], box[2 * a]);
    both[2 * a + 1] = std::max(pointBounds[2 * a + 1], box[2 * a + 1]);
    centre[a] = both[2 * a] / 2 + both[2 * a + 1] / 2;
  }
  double reach = 2 * diagonal(both);
  if (reach == 0)
    reach = 1; // one point and a box of no volume: any cube will do
  std::vector<double> far(3 * kFarPoints);
  for (int k = 0; k < kFarPoints; ++k)
    for (int a = 0; a < 3; ++a)
    {
      const double x = centre[a] + ((k >> a) & 1 ? reach : -reach);
      if (!std::isfinite(x))
        return {};
      far[3 * std::size_t(k) + a] = x;
    }
  return far;
}

} // namespace fd3
