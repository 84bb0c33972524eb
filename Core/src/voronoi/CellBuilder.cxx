// Building one cell from its generator's star (step 4 of VoronoiCells.cxx): the ring of the
// star's tetrahedra about each edge at the generator is one face, traced through a table of ring
// steps indexed by (ring, entry vertex), so that no map of tetrahedra is needed. A whole cell's
// rings go straight into the output, the Newell sums beside the walk; a cell that leaves the box
// becomes a polyhedron, which BoxClipper cuts by the box's walls.
#include "voronoi/CellBuilder.h"

#include "system/Platform.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fd3::voronoi
{
namespace
{
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

/// The local indices of a tetrahedron's vertices but one.
constexpr int kOthers[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};

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

} // namespace

CellBuilder::CellBuilder(const CellSources& sources, std::size_t vertices)
  : in_(sources), linkOf_(vertices, kNoLink)
{}

void CellBuilder::trace(std::uint32_t p)
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

template <bool Polyhedra>
void CellBuilder::emitWhole(
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
      out.cellPoints[out.cellPointStart[cell] + i] = pointOf_[i];
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

template void CellBuilder::emitWhole<true>(
  std::uint32_t, std::size_t, std::size_t, std::size_t, VoronoiCells&);
template void CellBuilder::emitWhole<false>(
  std::uint32_t, std::size_t, std::size_t, std::size_t, VoronoiCells&);

void CellBuilder::emitClipped(std::uint32_t p, std::uint32_t cell, Stretch& out)
{
  // The centres, scattered over the tetrahedra's order, are loaded while the rings are traced
  // rather than one cache miss after the other as the polyhedron is made.
  for (const std::uint32_t t : star_)
    prefetch(centre(t));
  traceRings();
  makePolyhedron();
  for (int wall = 0; wall < 6 && !cell_.neighbors.empty(); ++wall)
    clipper_.clip(cell_, wall, wall % 2 ? in_.box.hi[wall / 2] : in_.box.lo[wall / 2]);
  const Polyhedron& c = cell_;
  const std::size_t faces = c.neighbors.size();
  out.cells.push_back(cell);
  out.faceCounts.push_back(static_cast<std::uint32_t>(faces));
  crossingOf_.assign(c.x.size(), kNone);
  listed_.assign(c.x.size(), false);
  std::uint32_t points = 0;
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
      if (t == kNone && crossingOf_[v] == kNone)
      {
        crossingOf_[v] = crossings++;
        out.crossingPoints.insert(out.crossingPoints.end(), c.x[v].begin(), c.x[v].end());
      }
      const std::uint32_t id = t != kNone ? t : kOwnVertex | crossingOf_[v];
      out.vertices.push_back(id);
      if (!listed_[v])
      {
        listed_[v] = true;
        out.points.push_back(id);
        ++points;
      }
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
  out.pointCounts.push_back(points);
  out.volumes.push_back(sixVolume / 6);
  out.areas.push_back(twiceArea / 2);
}

template <typename LinkIndex, typename Step>
void CellBuilder::addStar(std::uint32_t p, LinkIndex linkIndex, Step step)
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

std::uint32_t CellBuilder::denseLinkIndex(std::uint32_t v)
{
  std::uint16_t& index = linkOf_[v];
  link_[met_] = v;
  const bool added = index == kNoLink;
  index = added ? static_cast<std::uint16_t>(met_) : index;
  met_ += added;
  return index;
}

std::uint32_t CellBuilder::largeLinkIndex(std::uint32_t v)
{
  const auto found = linkOfLarge_.emplace(v, static_cast<std::uint32_t>(met_));
  if (found.second)
    link_[met_++] = v;
  return found.first->second;
}

const CellBuilder::RingStep& CellBuilder::stepAt(std::uint64_t key) const
{
  static const RingStep none = {0, 0, 0}; // of no cell: stamps start at 1
  if (link_.size() <= kDenseLinks)
    return steps_[key];
  const auto found = stepsLarge_.find(key);
  return found == stepsLarge_.end() ? none : found->second;
}

void CellBuilder::traceRings()
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

void CellBuilder::makePolyhedron()
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

} // namespace fd3::voronoi
