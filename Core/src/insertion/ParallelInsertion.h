// The regions of a parallel insertion pass (ParallelInsertion.cxx).
#ifndef fd3_ParallelInsertion_h
#define fd3_ParallelInsertion_h

#include "fd3/BulkAllocator.h"
#include "insertion/Inserter.h"
#include "system/Platform.h"
#include "system/Threads.h"

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fd3
{

/// Boxes for `parts` threads holding about as many of a pass's points each: a kd split whose
/// level d cuts across axes[d], at quantiles of a sample of the points.
class Partition
{
public:
  Partition(const Mesh& mesh, const IdArray& vertices, int parts, const std::vector<int>& axes,
    ThreadTeam& team);
  int parts() const { return static_cast<int>(regions_.size()); }
  const Region& region(int k) const { return regions_[static_cast<std::size_t>(k)]; }
  /// The region that holds p (as Region::contains() decides).
  int regionOf(const double* p) const;

private:
  struct Node
  {
    int axis; ///< < 0 for a leaf
    double cut;
    int below; ///< a leaf's region
    int above;
  };
  /// Cuts samples [begin, end) of `region` across `axis` at their quantile left/parts, and moves
  /// those below the cut to the front: the cut and where those above begin.
  std::pair<double, std::size_t> cut(
    std::size_t begin, std::size_t end, int left, int parts, int axis, const Region& region);

  using Point = std::array<double, 3>;
  std::vector<Point, BulkAllocator<Point>> sample_; // not zeroed first, on the calling thread
  std::vector<Node> nodes_;                         // nodes_[0]: the root
  std::vector<Region> regions_;
};

/// A pass's points, as stretches of ranks [0, count), one per thread: each thread takes its own
/// stretch's points one by one from its start, and a thread whose stretch is spent takes the far
/// half of what is left of the longest one. Insertions cost more in some stretches of the curve
/// than in others (the inner side of a torus), and equal stretches would leave threads idle. Any
/// thread may call next() for its own stretch while others do for theirs. Only the stretch of a
/// thread that has had about as much CPU time in the pass as the one splitting it is split: one
/// that is long because its points cost more, not because its thread waited for a core. With a
/// core per thread that is every thread; where threads outnumber cores, the first to run would
/// otherwise take every stretch, and their CPU times would no longer model a core per thread.
class SharedStretches
{
public:
  SharedStretches(std::size_t count, std::size_t parts);
  /// The next rank for thread k, or false when no stretch has enough left to split.
  bool next(std::size_t k, std::size_t& rank);
  /// Empties thread k's stretch and returns what was left of it, [begin, end).
  std::pair<std::size_t, std::size_t> takeRest(std::size_t k);

private:
  // A stretch [begin, end) in one word, begin in the low half: its thread advances begin and a
  // thread that splits it lowers end, each by compare-and-swap.
  struct alignas(64) Stretch
  {
    std::atomic<std::uint64_t> range{0};
    // Set by its thread on its first next(), before `started`.
    ThreadCpuClock clock;
    double startCpu = 0;
    std::atomic<bool> started{false};
  };
  static std::uint64_t pack(std::size_t begin, std::size_t end)
  {
    return std::uint64_t(begin) | (std::uint64_t(end) << 32);
  }
  static std::size_t beginOf(std::uint64_t range) { return std::size_t(range & 0xFFFFFFFFu); }
  static std::size_t endOf(std::uint64_t range) { return std::size_t(range >> 32); }
  /// Moves the far half of the longest stretch to thread k's; false when none has enough left.
  bool split(std::size_t k);
  /// Its thread's CPU seconds in the pass so far; < 0 before it starts.
  static double cpuSeconds(const Stretch& stretch);

  // Fewer points than this are left to their thread: a split costs an insertion's walk there.
  static constexpr std::size_t kLeastToSplit = 64;
  // A stretch is split when its thread's CPU time in the pass is this share of the splitter's or
  // more. Threads that each have a core differ by their start only; threads that share cores by
  // the scheduler's turns, by a quarter and more over a short pass, and a looser share let
  // threads that had their turn first take what others would have done.
  static constexpr double kBusyShare = 0.95;
  std::vector<Stretch> stretches_;
};

} // namespace fd3

#endif
