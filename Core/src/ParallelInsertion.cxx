// Parallel insertion of one BRIO round: its points are split by count into one box per thread (a
// kd split), each thread inserts the points of its box, in curve order, changing only tetrahedra
// whose four vertices are in its box (Region, in Inserter.h: no locks, no two threads ever touch
// one tetrahedron). An insertion that would reach outside its box is put off. A second pass splits
// the points put off along other axes, so that few of them lie near its cuts; what is left goes in
// serially. Design read from HXT's partitioned insertion (Marot, Pellerin, Remacle 2019); code ours.
//
// The output does not depend on the number of threads or on their timing: with exact predicates
// and ties broken by an order of the points' coordinates alone (perturbationKey(), Predicates.h),
// the Delaunay triangulation is unique, and every point is inserted in one pass or another.
#include "Triangulator.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <numeric>
#include <system_error>
#include <thread>

namespace fd3
{
namespace
{
/// Boxes for `parts` threads holding about as many of `vertices` each (recursive cuts at quantiles).
/// Cut axes cycle through the set's axes from the longest. The points a pass puts off crowd around
/// its cuts, so the next pass, cut across the longest axis of their box, cuts across those.
class Partition
{
public:
  Partition(const Mesh& mesh, std::vector<VertId> vertices, int parts)
    : mesh_(mesh), ids_(std::move(vertices))
  {
    Box box = Box::around(mesh.point(ids_[0]));
    for (VertId v : ids_)
      box.include(mesh.point(v));
    std::iota(axes_, axes_ + 3, 0);
    std::sort(axes_, axes_ + 3, [&box](int a, int b) { return box.extent(a) > box.extent(b); });
    split(0, ids_.size(), parts, 0, Region());
  }
  const std::vector<Region>& regions() const { return regions_; }

private:
  void split(std::size_t begin, std::size_t end, int parts, int depth, const Region& region)
  {
    if (parts == 1)
    {
      regions_.push_back(region);
      return;
    }
    const int axis = axes_[depth % 3];
    const int left = parts / 2;
    auto coordinate = [&](VertId v) { return mesh_.point(v)[axis]; };
    const std::size_t cut = begin + (end - begin) * left / parts;
    double at = cut < end ? 0.0 : region.hi[axis];
    if (cut < end)
    {
      std::nth_element(ids_.begin() + begin, ids_.begin() + cut, ids_.begin() + end,
        [&](VertId a, VertId b) { return coordinate(a) < coordinate(b); });
      at = coordinate(ids_[cut]);
    }
    const std::size_t middle =
      static_cast<std::size_t>(std::partition(ids_.begin() + begin, ids_.begin() + end,
                                 [&](VertId v) { return coordinate(v) < at; }) -
        ids_.begin());
    Region below = region, above = region;
    below.hi[axis] = at;
    above.lo[axis] = at;
    split(begin, middle, left, depth + 1, below);
    split(middle, end, parts - left, depth + 1, above);
  }

  const Mesh& mesh_;
  std::vector<VertId> ids_;
  int axes_[3];
  std::vector<Region> regions_;
};

/// The least share of its points that a pass on `threads` threads must put in to be faster than
/// inserting them all serially, if a put-off insertion costs half of one that goes in (it stops
/// at the first tetrahedron outside its region, in the walk or the cavity). A pass with yield y
/// costs y/threads + (1-y)/(2 threads) and leaves 1-y to the serial pass.
double worthwhileYield(int threads)
{
  return 0.5 / (threads - 1 + 0.5);
}

/// Threads that are joined however the scope is left: a std::thread destroyed while joinable
/// terminates the process, which a failed start or an exception would otherwise cause.
class JoinedThreads
{
public:
  JoinedThreads() = default;
  JoinedThreads(const JoinedThreads&) = delete;
  JoinedThreads& operator=(const JoinedThreads&) = delete;
  ~JoinedThreads() { joinAll(); }
  /// Starts f(k) on a thread of its own; false when the system could not start one.
  template <typename F>
  bool start(F& f, std::size_t k)
  {
    try
    {
      threads_.emplace_back(f, k);
      return true;
    }
    catch (const std::system_error&)
    {
      return false;
    }
  }
  void joinAll()
  {
    for (std::thread& thread : threads_)
      if (thread.joinable())
        thread.join();
  }

private:
  std::vector<std::thread> threads_;
};
} // namespace

bool Triangulator::insertInParallel(
  std::vector<VertId> vertices, const std::function<bool(double)>& progress)
{
  const int threads = static_cast<int>(inserters_.size());
  for (int pass = 0; pass < 2 && !vertices.empty() && !stop_; ++pass)
  {
    if (passYield_[pass] < worthwhileYield(threads))
    {
      // Tried again once the guess, doubled every round left out, says so: later rounds, denser,
      // may do better.
      passYield_[pass] *= 2;
      break;
    }
    const std::size_t count = vertices.size();
    vertices = runPass(vertices, Partition(mesh_, vertices, threads).regions(), progress);
    passYield_[pass] = 1.0 - double(vertices.size()) / double(count);
  }
  std::sort(vertices.begin(), vertices.end()); // back to curve order
  return !stop_ &&
    insertSerially(
      vertices.size(), [&vertices](std::size_t i) { return vertices[i]; }, progress);
}

std::vector<std::vector<VertId>> Triangulator::shareOut(
  const std::vector<VertId>& vertices, const std::vector<Region>& regions) const
{
  std::vector<std::vector<VertId>> share(regions.size());
  for (VertId v : vertices)
    for (std::size_t k = 0; k < regions.size(); ++k)
      if (regions[k].contains(point(v)))
      {
        share[k].push_back(v);
        break;
      }
  return share;
}

// Before any thread runs, so that the search may read the whole mesh: the start is a tetrahedron
// in conflict with the first point of the share that has one in the region; the points before it
// are put off.
void Triangulator::startInRegions(const std::vector<Region>& regions,
  std::vector<std::vector<VertId>>& share, std::vector<std::vector<VertId>>& putOff)
{
  for (std::size_t k = 0; k < regions.size(); ++k)
  {
    Inserter& inserter = *inserters_[k];
    std::size_t first = 0;
    for (; first < share[k].size(); ++first)
    {
      inserter.unrestricted();
      const TetId start = inserter.locateForStart(share[k][first]);
      inserter.restrictTo(regions[k], start);
      if (inserter.isOwned(start))
        break;
    }
    putOff[k].assign(share[k].begin(), share[k].begin() + static_cast<std::ptrdiff_t>(first));
    share[k].erase(share[k].begin(), share[k].begin() + static_cast<std::ptrdiff_t>(first));
  }
}

std::vector<VertId> Triangulator::runPass(const std::vector<VertId>& vertices,
  const std::vector<Region>& regions, const std::function<bool(double)>& progress)
{
  const std::size_t threads = regions.size();
  makeRoomFor(vertices.size());
  std::vector<std::vector<VertId>> share = shareOut(vertices, regions);
  std::vector<std::vector<VertId>> putOff(threads);
  startInRegions(regions, share, putOff);

  passDone_ = 0;
  std::vector<std::exception_ptr> failures(threads);
  std::atomic<std::size_t> finished{0};
  auto work = [&](std::size_t k) {
    try
    {
      Inserter& inserter = *inserters_[k];
      const std::vector<VertId>& mine = share[k];
      for (std::size_t i = 0; i < mine.size(); ++i)
      {
        if (i % 256 == 0 &&
          (stop_ || (k == 0 && i % kProgressInterval == 0 && !reportProgress(progress))))
        {
          putOff[k].insert(
            putOff[k].end(), mine.begin() + static_cast<std::ptrdiff_t>(i), mine.end());
          break;
        }
        if (inserter.insert(mine[i]) == Inserter::Outcome::Deferred)
          putOff[k].push_back(mine[i]);
        else
          passDone_.fetch_add(1, std::memory_order_relaxed);
      }
    }
    catch (...)
    {
      failures[k] = std::current_exception();
      stop_ = true;
    }
    finished.fetch_add(1);
  };
  JoinedThreads helpers;
  std::vector<std::size_t> unstarted; // regions no thread could be started for: this one takes them
  for (std::size_t k = 1; k < threads; ++k)
    if (!helpers.start(work, k))
      unstarted.push_back(k);
  work(0);
  for (const std::size_t k : unstarted)
    work(k);
  // This thread alone reports progress, also while the others finish; a callback that throws
  // stops them, and the threads are joined before anything unwinds.
  while (finished < threads)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    try
    {
      reportProgress(progress);
    }
    catch (...)
    {
      if (!failures[0])
        failures[0] = std::current_exception();
      stop_ = true;
    }
  }
  helpers.joinAll();
  done_ += passDone_;
  passDone_ = 0;
  for (const std::exception_ptr& failure : failures)
    if (failure)
      std::rethrow_exception(failure);
  std::vector<VertId> left;
  for (const auto& list : putOff)
    left.insert(left.end(), list.begin(), list.end());
  return left;
}

} // namespace fd3
