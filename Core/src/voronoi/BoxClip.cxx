// Clipping a cell by the box (step 5 of VoronoiCells.cxx), one wall at a time: each face keeps
// its inside part, an edge's crossing of the wall is computed from its two ends in
// lexicographic order and set exactly on the wall, so every cell around that edge computes the
// same double, and the crossings close a new face on the wall.
#include "voronoi/BoxClip.h"

#include "fd3/Voronoi.h"

#include <utility>

namespace fd3::voronoi
{
namespace
{
bool lexicographicallyLess(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return a[0] != b[0] ? a[0] < b[0] : (a[1] != b[1] ? a[1] < b[1] : a[2] < b[2]);
}

} // namespace

void BoxClipper::clip(Polyhedron& c, int wall, double bound)
{
  const int axis = wall / 2;
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
      const std::uint32_t x = outside(u) ? (on(w) ? w : crossing(c, w, u, axis, bound))
                                         : (on(u) ? u : crossing(c, u, w, axis, bound));
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

void BoxClipper::append(std::vector<std::uint32_t>& loops, std::size_t kept, std::uint32_t v)
{
  if (loops.size() == kept || loops.back() != v)
    loops.push_back(v);
}

std::uint32_t BoxClipper::crossing(
  Polyhedron& c, std::uint32_t inside, std::uint32_t outside, int axis, double bound)
{
  for (const auto& known : crossings_)
    if ((known[0] == inside && known[1] == outside) || (known[0] == outside && known[1] == inside))
      return known[2];
  std::array<double, 3> a = c.x[inside], b = c.x[outside];
  if (lexicographicallyLess(b, a))
    std::swap(a, b);
  const double t = (bound - a[axis]) / (b[axis] - a[axis]);
  std::array<double, 3> x;
  for (int k = 0; k < 3; ++k)
    x[k] = a[k] + t * (b[k] - a[k]);
  x[axis] = bound;
  const auto id = static_cast<std::uint32_t>(c.x.size());
  c.x.push_back(x);
  c.tet.push_back(kNone);
  crossings_.push_back({inside, outside, id});
  return id;
}

void BoxClipper::closeCap(std::vector<std::uint32_t>& loops, std::vector<std::uint32_t>& faceStart,
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

} // namespace fd3::voronoi
