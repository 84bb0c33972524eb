// Parallel insertion of one BRIO round, in up to three passes, then serially what they leave:
//
// * A region pass, in rounds of Options::pointsPerThread points per thread or more (smaller
//   rounds go to the locking passes whole): the points are split by count into one box per thread
//   (a kd split), and each thread inserts the points of its box, in curve order, changing only
//   tetrahedra whose four vertices are in its box (Region, in Inserter.h: no locks, no two
//   threads ever touch one tetrahedron). An insertion that would reach outside its box is put
//   off. The cut axes follow the mesh's tetrahedra: on a surface sample they are thin across the
//   surface's long directions, and a cut across the axes along which they are thin crosses few of
//   them; volume data, whose tetrahedra are as wide every way, is cut across its longest axes in
//   turn. A region whose first eighth puts nearly every point off sends the rest to the locking
//   passes. Design read from HXT's partitioned insertion (Marot, Pellerin, Remacle 2019); code
//   ours.
// * Locking passes: each thread takes a stretch of the curve (and, once done, the far half of what
//   is left of the longest other, SharedStretches) and holds every tetrahedron it reads
//   or writes in an owner table (one byte per slot, compare-and-swap), hand over hand along its
//   walk; an insertion that meets a tetrahedron another thread holds lets go of all and is put
//   off. It needs no boxes, so it takes what reaches across any box: the points near the region
//   pass's cuts, and the convex surface samples whose hull faces and inner tetrahedra reach across
//   the whole set (a cylinder's hull has faces as long as the cylinder, and its inner tetrahedra
//   span its width). Design read from geogram's parallel Delaunay (per-tetrahedron ownership,
//   rollback, retry later); code ours. An owner check costs an atomic operation per tetrahedron,
//   which the region pass saves, so the region pass goes first where it puts most points in.
//
// The output does not depend on the number of threads or on their timing: with exact predicates
// and ties broken by an order of the points' coordinates alone (perturbationKey(), Predicates.h),
// the Delaunay triangulation is unique, and every point is inserted in one pass or another.
#include "insertion/ParallelInsertion.h"

#include "insertion/Triangulator.h"
#include "system/Threads.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace fd3
{
namespace
{
// A region pass pays for itself where it puts at least this share of its points in: the locking
// passes after it take the rest at about 1.35 times the cost of an unlocked insertion, and a
// put-off insertion costs about half of one that goes in, so with a yield y the region pass costs
// y + (1 - y)(0.5 + 1.35) against 1.35 for locking passes alone.
constexpr double kWorthwhileRegionYield = 0.6;
// The partition's cuts come from a sample of this many points per region (about 4% imbalance).
constexpr std::size_t kSamplePerRegion = 512;
// Tetrahedra whose extents choose the cut axes.
constexpr std::size_t kShapeSample = 512;
// Points whose box the cut axes are chosen in.
constexpr std::size_t kBoxSample = 1024;

/// Whether the first insertions of a region's share (`tried` of `share`, `putOff` of them put
/// off) and of the whole pass (`passTried`, `passPutOff`, over `parts` regions) say that the rest
/// of the share had better go to the locking passes at once: on a convex surface sample, whose
/// hull faces and inner tetrahedra reach across the whole set, nearly all would be put off, each
/// after a walk and part of a cavity. The trial is long: where a cut runs through a block of the
/// curve, a region's share may begin with a sliver along the cut, all of it put off. And the pass
/// must fare as badly: a region of clustered points may put off every point of its first cluster
/// and few of the next.
bool hopelessRegion(std::size_t tried, std::size_t share, std::size_t putOff, std::size_t passTried,
  std::size_t passPutOff, std::size_t parts)
{
  constexpr std::size_t kLeastTrial = 1024;
  constexpr double kHopelessYield = 0.25;
  const auto hopeless = [](std::size_t n, std::size_t off) {
    return double(off) > (1.0 - kHopelessYield) * double(n);
  };
  return tried >= std::max(kLeastTrial, share / 8) && hopeless(tried, putOff) &&
    passTried >= parts * kLeastTrial / 2 && hopeless(passTried, passPutOff);
}

/// The least share of its points that a locking pass on `threads` threads must put in to be faster
/// than inserting them all serially, if a put-off insertion costs half of one that goes in (it
/// stops at the first tetrahedron held by another). A pass with yield y costs
/// y/threads + (1-y)/(2 threads) and leaves 1-y to the serial pass.
double worthwhileYield(std::size_t threads)
{
  return 0.5 / (double(threads) - 1 + 0.5);
}
} // namespace

Partition::Partition(const Mesh& mesh, const IdArray& vertices, int parts,
  const std::vector<int>& axes, ThreadTeam& team)
{
  const std::size_t wanted = kSamplePerRegion * std::size_t(parts);
  const std::size_t stride = std::max<std::size_t>(1, vertices.size() / wanted);
  // The coordinates themselves, a cache miss each, gathered on every thread: the selections
  // below read each several times, in no order.
  sample_.resize((vertices.size() + stride - 1) / stride);
  team.forRanges(sample_.size(), "regions", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* p = mesh.point(vertices[i * stride]);
      sample_[i] = {p[0], p[1], p[2]};
    }
  });
  // Level by level, the nodes of a level each on its own thread (their samples are disjoint).
  struct Pending
  {
    std::size_t begin, end;
    int parts, node;
    Region region;
  };
  std::vector<Pending> level{{0, sample_.size(), parts, 0, Region()}};
  nodes_.emplace_back();
  for (std::size_t depth = 0; !level.empty(); ++depth)
  {
    const int axis = axes[std::min(depth, axes.size() - 1)];
    std::vector<std::pair<double, std::size_t>> cuts(level.size());
    team.run(
      level.size(),
      [&](std::size_t k) {
        const Pending& node = level[k];
        if (node.parts > 1)
          cuts[k] = cut(node.begin, node.end, node.parts / 2, node.parts, axis, node.region);
      },
      team.newRecord("regions"));
    std::vector<Pending> next;
    for (std::size_t k = 0; k < level.size(); ++k)
    {
      const Pending& node = level[k];
      if (node.parts == 1)
      {
        nodes_[node.node] = Node{-1, 0.0, static_cast<int>(regions_.size()), -1};
        regions_.push_back(node.region);
        continue;
      }
      const auto [at, middle] = cuts[k];
      const int lower = static_cast<int>(nodes_.size()), upper = lower + 1;
      nodes_.resize(nodes_.size() + 2);
      nodes_[node.node] = Node{axis, at, lower, upper};
      Region below = node.region, above = node.region;
      below.hi[axis] = at;
      above.lo[axis] = at;
      const int left = node.parts / 2;
      next.push_back({node.begin, middle, left, lower, below});
      next.push_back({middle, node.end, node.parts - left, upper, above});
    }
    level = std::move(next);
  }
}

int Partition::regionOf(const double* p) const
{
  int node = 0;
  while (nodes_[node].axis >= 0)
    node = p[nodes_[node].axis] < nodes_[node].cut ? nodes_[node].below : nodes_[node].above;
  return nodes_[node].below;
}

std::pair<double, std::size_t> Partition::cut(
  std::size_t begin, std::size_t end, int left, int parts, int axis, const Region& region)
{
  const auto coordinate = [axis](const Point& p) { return p[std::size_t(axis)]; };
  const auto first = sample_.begin() + static_cast<std::ptrdiff_t>(begin);
  const auto last = sample_.begin() + static_cast<std::ptrdiff_t>(end);
  const auto quantile = first + static_cast<std::ptrdiff_t>((end - begin) * left / parts);
  double at = region.hi[axis]; // no sample point: all below
  if (quantile < last)
  {
    std::nth_element(first, quantile, last,
      [&](const Point& a, const Point& b) { return coordinate(a) < coordinate(b); });
    at = coordinate(*quantile);
  }
  const std::size_t middle = static_cast<std::size_t>(
    std::partition(first, last, [&](const Point& p) { return coordinate(p) < at; }) -
    sample_.begin());
  return {at, middle};
}

SharedStretches::SharedStretches(std::size_t count, std::size_t parts) : stretches_(parts)
{
  if (count > 0xFFFFFFFFu)
    throw std::length_error("fd3: a pass of more than 2^32 points");
  for (std::size_t k = 0; k < parts; ++k)
  {
    const Part part = partOf(count, k, parts);
    stretches_[k].range.store(pack(part.first, part.last));
  }
}

bool SharedStretches::next(std::size_t k, std::size_t& rank)
{
  Stretch& stretch = stretches_[k];
  std::atomic<std::uint64_t>& mine = stretch.range;
  if (!stretch.started.load(std::memory_order_relaxed))
  {
    stretch.clock = ThreadCpuClock::ofThisThread();
    stretch.startCpu = stretch.clock.seconds();
    stretch.started.store(true, std::memory_order_release);
  }
  for (;;)
  {
    std::uint64_t range = mine.load(std::memory_order_relaxed);
    while (beginOf(range) < endOf(range))
      if (mine.compare_exchange_weak(
            range, pack(beginOf(range) + 1, endOf(range)), std::memory_order_relaxed))
      {
        rank = beginOf(range);
        return true;
      }
    if (!split(k))
      return false;
  }
}

double SharedStretches::cpuSeconds(const Stretch& stretch)
{
  if (!stretch.started.load(std::memory_order_acquire))
    return -1.0;
  return stretch.clock.seconds() - stretch.startCpu;
}

bool SharedStretches::split(std::size_t k)
{
  const double mine = cpuSeconds(stretches_[k]);
  // Stretches found waiting for a core in this call: the next longest is tried instead.
  std::vector<char> waiting(stretches_.size(), 0);
  for (;;)
  {
    std::size_t longest = k, most = 0;
    for (std::size_t j = 0; j < stretches_.size(); ++j)
    {
      const std::uint64_t range = stretches_[j].range.load(std::memory_order_relaxed);
      const std::size_t left = endOf(range) - std::min(beginOf(range), endOf(range));
      if (!waiting[j] && left > most)
      {
        most = left;
        longest = j;
      }
    }
    if (most < kLeastToSplit)
      return false;
    if (cpuSeconds(stretches_[longest]) < kBusyShare * mine)
    {
      waiting[longest] = 1;
      continue;
    }
    std::uint64_t range = stretches_[longest].range.load(std::memory_order_relaxed);
    const std::size_t begin = beginOf(range), end = endOf(range);
    if (begin + kLeastToSplit > end)
      continue;
    const std::size_t middle = begin + (end - begin) / 2;
    if (stretches_[longest].range.compare_exchange_strong(
          range, pack(begin, middle), std::memory_order_relaxed))
    {
      stretches_[k].range.store(pack(middle, end), std::memory_order_relaxed);
      return true;
    }
  }
}

std::pair<std::size_t, std::size_t> SharedStretches::takeRest(std::size_t k)
{
  const std::uint64_t range = stretches_[k].range.exchange(0, std::memory_order_relaxed);
  return {std::min(beginOf(range), endOf(range)), endOf(range)};
}

std::vector<int> Triangulator::cutAxes(const IdArray& vertices) const
{
  Bounds box;
  for (std::size_t i = 0; i < vertices.size();
       i += std::max<std::size_t>(1, vertices.size() / kBoxSample))
    box.include(point(vertices[i]));
  // Mean extent of the mesh's tetrahedra along each axis, over the tetrahedra of vertices before
  // the round (whose records are all current between passes; a point added as a duplicate of a
  // vertex has none).
  double width[3] = {0, 0, 0};
  const VertId inserted = vertices.front();
  for (VertId v = 0; v < inserted; v += std::max<VertId>(1, inserted / kShapeSample))
  {
    if (mesh_.vertices[v].tet == kNoTet)
      continue;
    VertId tv[4];
    mesh_.tets.vertices(mesh_.vertices[v].tet, tv);
    if (tv[3] == kInfinite)
      continue;
    for (int a = 0; a < 3; ++a)
    {
      double lo = point(tv[0])[a], hi = lo;
      for (int k = 1; k < 4; ++k)
      {
        lo = std::min(lo, point(tv[k])[a]);
        hi = std::max(hi, point(tv[k])[a]);
      }
      width[a] += hi - lo;
    }
  }
  // A cut across axis a crosses the tetrahedra within their width of it: a share of the points of
  // about width/extent per cut. Each level doubles the pieces along the axis that adds the least.
  double share[3], pieces[3] = {1, 1, 1};
  for (int a = 0; a < 3; ++a)
    share[a] = box.extent(a) > 0 ? (width[a] + 1e-300) / box.extent(a)
                                 : std::numeric_limits<double>::infinity();
  std::vector<int> axes;
  for (int parts = 1; parts < team_.size(); parts *= 2)
  {
    int a = 0;
    for (int b = 1; b < 3; ++b)
      if (pieces[b] * share[b] < pieces[a] * share[a])
        a = b;
    axes.push_back(a);
    pieces[a] *= 2;
  }
  return axes;
}

bool Triangulator::insertInParallel(IdArray vertices, const std::function<bool(double)>& progress)
{
  // A region pass takes a region per thread, of pointsPerThread points at least: smaller regions
  // put off a third of their points and more at their borders. Fewer regions than threads would
  // leave threads idle while the locking pass, which shares a round of any size out over all of
  // them, takes n / T at about 1.25 times the cost of a region's insertion, against n / R.
  const std::size_t regions = static_cast<std::size_t>(team_.size());
  if (vertices.size() / std::max<std::size_t>(1, mesh_.options.pointsPerThread) >= regions &&
    !stop_)
  {
    // Tried again once the guess, up 10% a round, says so: later rounds, with more points per
    // region, may do a little better; one far below never is (its rounds only grow).
    if (regionYield_ < kWorthwhileRegionYield)
      regionYield_ *= 1.1;
    else
    {
      const std::vector<int> axes = cutAxes(vertices);
      IdArray left = runRegionPass(
        vertices, Partition(mesh_, vertices, static_cast<int>(regions), axes, team_), progress);
      team_.release(vertices, "regions");
      vertices = std::move(left);
    }
  }
  // Each locking pass takes half the threads of the one before: what a pass put off lies where
  // threads met, and fewer, longer stretches meet less (clustered points put off many, their
  // cavities reaching across the empty space between clusters).
  for (int pass = 0; pass < kLockingPasses && !stop_; ++pass)
  {
    const std::size_t parts = std::min<std::size_t>(
      std::size_t(team_.size()) >> pass, vertices.size() / kMinPointsPerThread);
    if (parts < 2)
      break;
    if (lockingYield_[pass] < worthwhileYield(parts))
    {
      lockingYield_[pass] *= 2;
      break;
    }
    IdArray left = runLockingPass(vertices, parts, pass, progress);
    lockingYield_[pass] = 1.0 - double(left.size()) / double(vertices.size());
    team_.release(vertices, "regions");
    vertices = std::move(left);
  }
  return !stop_ &&
    insertSerially(
      vertices.size(), [&vertices](std::size_t i) { return vertices[i]; }, progress);
}

// Read only, while no thread writes: the start is a tetrahedron in conflict with the first point
// of the share that has one in the region; the points before it are put off.
void Triangulator::startInRegion(
  std::size_t k, const Region& region, std::vector<VertId>& share, std::vector<VertId>& putOff)
{
  Inserter& inserter = *inserters_[k];
  std::size_t first = 0;
  for (; first < share.size(); ++first)
  {
    inserter.unrestricted();
    const TetId start = inserter.locateForStart(share[first]);
    inserter.restrictTo(region, start);
    if (inserter.isOwned(start))
      break;
  }
  putOff.assign(share.begin(), share.begin() + static_cast<std::ptrdiff_t>(first));
  share.erase(share.begin(), share.begin() + static_cast<std::ptrdiff_t>(first));
}

// Each thread sorts a stretch of the points into regions; then each gathers its region's points
// from every stretch, in curve order, and finds its start.
void Triangulator::shareOut(const IdArray& vertices, const Partition& partition,
  std::vector<std::vector<VertId>>& share, std::vector<std::vector<VertId>>& putOff)
{
  const std::size_t parts = static_cast<std::size_t>(partition.parts());
  std::vector<std::vector<std::vector<VertId>>> byStretch(
    parts, std::vector<std::vector<VertId>>(parts));
  ThreadedWork& record = team_.newRecord("regions");
  team_.run(
    parts,
    [&](std::size_t k) {
      const Part part = partOf(vertices.size(), k, parts);
      for (std::size_t i = part.first; i < part.last; ++i)
        byStretch[k][partition.regionOf(point(vertices[i]))].push_back(vertices[i]);
    },
    record);
  share.assign(parts, {});
  putOff.assign(parts, {});
  team_.run(
    parts,
    [&](std::size_t k) {
      for (std::size_t c = 0; c < parts; ++c)
        share[k].insert(share[k].end(), byStretch[c][k].begin(), byStretch[c][k].end());
      startInRegion(k, partition.region(static_cast<int>(k)), share[k], putOff[k]);
    },
    record);
}

IdArray Triangulator::runRegionPass(
  const IdArray& vertices, const Partition& partition, const std::function<bool(double)>& progress)
{
  makeRoomFor(vertices.size());
  std::vector<std::vector<VertId>> share, putOff;
  shareOut(vertices, partition, share, putOff);
  std::vector<std::size_t> tried(share.size(), 0);
  std::atomic<std::size_t> passTried{0}, passPutOff{0}; // every thread's, every 256 tries
  passDone_ = 0;
  auto work = [&](std::size_t k) {
    try
    {
      Inserter& inserter = *inserters_[k];
      const std::vector<VertId>& mine = share[k];
      const std::size_t putOffAtStart = putOff[k].size();
      std::size_t i = 0, triedReported = 0, putOffReported = 0;
      // The shared counts take each thread's every 256 tries: an atomic add on every insertion
      // moved their cache line from core to core.
      const auto report = [&] {
        const std::size_t putOffSoFar = putOff[k].size() - putOffAtStart;
        const std::size_t tries = i - triedReported, putOffNow = putOffSoFar - putOffReported;
        passTried.fetch_add(tries, std::memory_order_relaxed);
        passPutOff.fetch_add(putOffNow, std::memory_order_relaxed);
        passDone_.fetch_add(tries - putOffNow, std::memory_order_relaxed);
        triedReported = i;
        putOffReported = putOffSoFar;
      };
      for (; i < mine.size(); ++i)
      {
        if (i % 256 == 0)
        {
          report();
          if (stop_ || (k == 0 && i % kProgressInterval == 0 && !reportProgress(progress)) ||
            hopelessRegion(i, mine.size(), putOffReported,
              passTried.load(std::memory_order_relaxed), passPutOff.load(std::memory_order_relaxed),
              share.size()))
          {
            putOff[k].insert(
              putOff[k].end(), mine.begin() + static_cast<std::ptrdiff_t>(i), mine.end());
            break;
          }
        }
        if (inserter.insert(mine[i]) == Inserter::Outcome::Deferred)
          putOff[k].push_back(mine[i]);
      }
      if (i == mine.size()) // else the rest, put off untried, was after the last report
        report();
      tried[k] = putOffAtStart + i;
      std::vector<VertId>().swap(share[k]); // its pages given back on this thread
    }
    catch (...)
    {
      stop_ = true;
      throw;
    }
  };
  ThreadedWork& record = team_.newRecord("insertion region pass");
  record.points = vertices.size();
  team_.run(share.size(), work, record, progressPoll(progress));
  // The yield of the insertions tried: the points of a hopeless region that were not are no guide
  // to the others'.
  const std::size_t triedInAll = std::accumulate(tried.begin(), tried.end(), std::size_t(0));
  regionYield_ = triedInAll > 0 ? double(passDone_) / double(triedInAll) : 0.0;
  done_ += passDone_;
  passDone_ = 0;
  return mergeAscending(vertices, putOff, record);
}

IdArray Triangulator::mergeAscending(
  const IdArray& vertices, const std::vector<std::vector<VertId>>& putOff, ThreadedWork& pass)
{
  pass.left = 0;
  for (const auto& list : putOff)
    pass.left += list.size();
  if (pass.left == 0)
    return {};
  ThreadedWork& record = team_.newRecord("regions");
  const VertId first = vertices.front();
  const std::size_t span = std::size_t(vertices.back() - first) + 1;
  std::vector<std::uint8_t, BulkAllocator<std::uint8_t>> marked(span);
  const std::size_t parts = team_.partsFor(span);
  team_.run(
    parts,
    [&](std::size_t k) {
      const Part part = partOf(span, k, parts);
      std::fill(marked.begin() + std::ptrdiff_t(part.first),
        marked.begin() + std::ptrdiff_t(part.last), std::uint8_t(0));
    },
    record);
  team_.run(
    putOff.size(),
    [&](std::size_t k) {
      for (const VertId v : putOff[k])
        marked[v - first] = 1;
    },
    record);
  return team_.indicesWhere(
    record, first, first + span, [&](std::size_t v) { return marked[v - first] != 0; });
}

void Triangulator::prepareOwners()
{
  const std::size_t slots = mesh_.tets.capacity();
  if (ownerSlots_ < slots)
  {
    if (owners_)
      team_.releasePages(owners_.get(), ownerSlots_ * sizeof(OwnerTable), "owners");
    owners_ = {
      static_cast<OwnerTable*>(detail::allocateBulk(slots * sizeof(OwnerTable))), Free{slots}};
    ownerSlots_ = slots;
    // Every slot free, written on every thread: calloc() would zero a block that its heap
    // recycles on this thread alone.
    OwnerTable* table = owners_.get();
    team_.forRanges(slots, "owners", [table](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
        new (table + t) OwnerTable(0);
    });
  }
  markFreeSlots(true);
}

void Triangulator::markFreeSlots(bool owned)
{
  team_.run(
    pools_.size(),
    [&](std::size_t k) {
      const auto owner = static_cast<std::uint8_t>(owned ? k + 1 : 0);
      for (const TetId t : pools_[k]->freeSlots())
        owners_.get()[t].store(owner, std::memory_order_relaxed);
    },
    team_.newRecord("owners"));
}

// Each thread takes a stretch of the curve, which keeps the threads far apart and their
// insertions' cavities apart but where two meet; one done with its own splits another's.
IdArray Triangulator::runLockingPass(
  const IdArray& vertices, std::size_t parts, int pass, const std::function<bool(double)>& progress)
{
  makeRoomFor(vertices.size());
  prepareOwners();
  SharedStretches stretches(vertices.size(), parts);
  std::vector<std::vector<VertId>> putOff(parts);
  passDone_ = 0;
  auto work = [&](std::size_t k) {
    Inserter& inserter = *inserters_[k];
    inserter.lockIn(owners_.get(), ownerSlots_, static_cast<std::uint8_t>(k + 1));
    try
    {
      std::size_t i = 0, inserted = 0; // inserted since the last report
      for (std::size_t tried = 0; stretches.next(k, i); ++tried)
      {
        if (tried % 256 == 0) // as in the region pass, the shared count every 256 tries
        {
          passDone_.fetch_add(std::exchange(inserted, 0), std::memory_order_relaxed);
          if (stop_ || (k == 0 && tried % kProgressInterval == 0 && !reportProgress(progress)))
          {
            const auto [begin, end] = stretches.takeRest(k);
            putOff[k].push_back(vertices[i]);
            putOff[k].insert(putOff[k].end(), vertices.begin() + static_cast<std::ptrdiff_t>(begin),
              vertices.begin() + static_cast<std::ptrdiff_t>(end));
            break;
          }
        }
        if (inserter.insert(vertices[i]) == Inserter::Outcome::Deferred)
          putOff[k].push_back(vertices[i]);
        else
          ++inserted;
      }
      passDone_.fetch_add(inserted, std::memory_order_relaxed);
    }
    catch (...)
    {
      inserter.unlocked();
      stop_ = true;
      throw;
    }
    inserter.unlocked();
  };
  ThreadedWork& record = team_.newRecord(kLockingPassNames[pass]);
  record.points = vertices.size();
  team_.run(parts, work, record, progressPoll(progress));
  done_ += passDone_;
  passDone_ = 0;
  // Between passes every slot is free again: live ones were let go after each insertion, and the
  // pools' free ones are marked for the next locking pass when it starts.
  markFreeSlots(false);
  return mergeAscending(vertices, putOff, record);
}

std::function<void()> Triangulator::progressPoll(const std::function<bool(double)>& progress)
{
  // This thread alone reports progress, also while the others finish; a callback that throws
  // stops them.
  return [this, &progress] {
    try
    {
      reportProgress(progress);
    }
    catch (...)
    {
      stop_ = true;
      throw;
    }
  };
}

} // namespace fd3
