// The threads of one triangulation: a team started once and given one fork-join per phase or
// insertion pass, each part's CPU time recorded (fd3::ThreadedWork) for the scaling model.
// std::thread rather than a task scheduler: Core stays free of VTK, and its parallel work is a
// few dozen fork-joins of equal parts, where a scheduler adds nothing but a dependency. The
// threads live as long as the team: starting 63 threads for each of the insertion's passes would
// cost the calling thread more than a pass takes on 64 cores.
#ifndef fd3_Threads_h
#define fd3_Threads_h

#include "fd3/Delaunay.h"
#include "system/Stretches.h"

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace fd3
{

/// The threads a request for `requested` starts: all hardware threads for 0 or less; else at most
/// kThreadsPerHardwareThread per hardware thread, or kMinThreadLimit where that is more (each
/// thread has its own scratch: beyond a few per hardware thread they only cost memory, and
/// kMinThreadLimit lets any machine run, and test, what a large one runs).
int boundedThreads(int requested);

/// Part k of [0, count) cut into `parts` contiguous parts, in order. A loop over a part takes its
/// bounds from here into locals: written in the loop's test, they were divided again on every
/// element, since the loop's stores might change the captured count, as far as the compiler knows.
struct Part
{
  std::size_t first, last;
};
inline Part partOf(std::size_t count, std::size_t k, std::size_t parts)
{
  return {count * k / parts, count * (k + 1) / parts};
}

class ThreadTeam
{
public:
  /// A team of `size` threads, the calling one included; the others start on the first run().
  explicit ThreadTeam(int size);
  ThreadTeam(const ThreadTeam&) = delete;
  ThreadTeam& operator=(const ThreadTeam&) = delete;
  ~ThreadTeam();

  int size() const { return size_; }

  /// Runs part(k) for every k < parts (at most size()): k = 0 on the calling thread, the others on
  /// the team's threads, or on the calling thread after its own part where the system could not
  /// start them all. While others still run, the calling thread calls `poll` every few
  /// milliseconds (progress). Each part's CPU time is added to record.threadSeconds[k]. The first
  /// exception of a part or of `poll` is rethrown once every part has ended; parts are not
  /// stopped by it (work that should stop early watches a flag that it and `poll` set).
  void run(std::size_t parts, const std::function<void(std::size_t)>& part, ThreadedWork& record,
    const std::function<void()>& poll = nullptr);

  /// A new record of threaded work, for run(). It stays where it is while more are made.
  ThreadedWork& newRecord(const char* phase);
  /// Every record so far, in the order made.
  std::vector<ThreadedWork> records() const { return {records_.begin(), records_.end()}; }

  /// The parts that `count` items make: one per thread, each of kMinItemsPerPart items or more.
  std::size_t partsFor(std::size_t count) const;
  /// Splits [0, count) into partsFor(count) contiguous ranges, in order, and runs f(k, begin, end)
  /// on range k, recorded as a phase named `phase`.
  void forRanges(std::size_t count, const char* phase,
    const std::function<void(std::size_t, std::size_t, std::size_t)>& f);
  static constexpr std::size_t kMinItemsPerPart = 4096;
  /// Runs write(k, begin, end, at) on stretch k of partsFor(last - first) consecutive stretches of
  /// [first, last), after each has counted with count(begin, end) what it will write: `at` is
  /// where stretch k's output starts, `written` where the first one's does (on return, where the
  /// last one's ends); write returns where its own output ends. With one stretch nothing is
  /// counted. Recorded in `record`.
  template <typename Count, typename Write>
  void countThenWrite(ThreadedWork& record, std::size_t first, std::size_t last,
    std::size_t& written, Count count, Write write);
  /// The i in [first, last) where keep(i) holds, ascending: each stretch counts its own, then
  /// writes them after the stretches before it (countThenWrite). Recorded in `record`.
  template <typename Keep>
  IdArray indicesWhere(ThreadedWork& record, std::size_t first, std::size_t last, Keep keep);
  /// Running sums: v[i] becomes v[0] + ... + v[i], each stretch of v summed on its own thread,
  /// then added to the sum of the stretches before it. Recorded as `phase`.
  template <typename Vector>
  void accumulate(Vector& v, const char* phase);
  /// forRanges() as Stretches, recorded as `phase` (the team must outlive it).
  Stretches stretches(const char* phase);
  /// Gives the whole pages of [begin, begin + bytes) back to the system on the team's threads
  /// (fd3::releasePages in Stretches.h), recorded as `phase`.
  void releasePages(void* begin, std::size_t bytes, const char* phase);
  /// Gives back v's memory beyond its size (fd3::releaseSpareCapacity) on the team's threads.
  template <typename T>
  void releaseSpareCapacity(std::vector<T, BulkAllocator<T>>& v, const char* phase)
  {
    releasePages(v.data() + v.size(), (v.capacity() - v.size()) * sizeof(T), phase);
  }
  /// Frees `v`, its pages given back on the team's threads first.
  template <typename T>
  void release(std::vector<T, BulkAllocator<T>>& v, const char* phase)
  {
    releasePages(v.data(), v.capacity() * sizeof(T), phase);
    std::vector<T, BulkAllocator<T>>().swap(v);
  }

private:
  void startHelpers();
  void serve(std::size_t k);
  void runPart(std::size_t k);

  /// Wakes helpers 2k and 2k + 1 where they have a part: helper k's children in a binary tree
  /// rooted at the calling thread (k = 0 wakes helper 1). Waking every helper from one thread
  /// cost it a system call's work per helper, every run: on 64 threads a third of its serial time.
  void wakeChildren(std::size_t k);

  // Where helper k waits for a run: its own, so that a run wakes only the helpers it needs.
  struct alignas(64) Seat
  {
    std::mutex mutex;
    std::condition_variable wake;
    std::size_t generation = 0;
    bool quit = false;
  };

  const int size_;
  std::vector<std::thread> helpers_; // helpers_[k - 1] runs part k
  std::unique_ptr<Seat[]> seats_;    // seats_[k - 1]: helper k's, all made before any helper
  bool started_ = false;

  std::mutex mutex_;
  std::condition_variable done_;
  // The job, set by run() before it wakes helper 1; each helper reads it after its seat's
  // generation moved on, which orders it after the writes.
  std::size_t parts_ = 0;
  std::size_t onHelpers_ = 0; // helpers 1..onHelpers_ run a part
  std::size_t finished_ = 0;
  const std::function<void(std::size_t)>* part_ = nullptr;
  ThreadedWork* record_ = nullptr;
  std::vector<std::exception_ptr> failures_;
  std::deque<ThreadedWork> records_; // a deque: a new record moves none of the others
};

template <typename Count, typename Write>
void ThreadTeam::countThenWrite(ThreadedWork& record, std::size_t first, std::size_t last,
  std::size_t& written, Count count, Write write)
{
  const std::size_t n = last - first, parts = partsFor(n);
  if (parts == 1)
  {
    run(
      1, [&](std::size_t) { written = write(0, first, last, written); }, record);
    return;
  }
  std::vector<std::size_t> offset(parts + 1, 0);
  run(
    parts,
    [&](std::size_t k) {
      const Part part = partOf(n, k, parts);
      offset[k + 1] = count(first + part.first, first + part.last);
    },
    record);
  offset[0] = written;
  for (std::size_t k = 0; k < parts; ++k)
    offset[k + 1] += offset[k];
  run(
    parts,
    [&](std::size_t k) {
      const Part part = partOf(n, k, parts);
      write(k, first + part.first, first + part.last, offset[k]);
    },
    record);
  written = offset[parts];
}

template <typename Keep>
IdArray ThreadTeam::indicesWhere(
  ThreadedWork& record, std::size_t first, std::size_t last, Keep keep)
{
  IdArray kept(last - first);
  std::size_t written = 0;
  countThenWrite(
    record, first, last, written,
    [&](std::size_t begin, std::size_t end) {
      std::size_t n = 0;
      for (std::size_t i = begin; i < end; ++i)
        n += keep(i);
      return n;
    },
    [&](std::size_t, std::size_t begin, std::size_t end, std::size_t next) {
      for (std::size_t i = begin; i < end; ++i)
        if (keep(i))
          kept[next++] = static_cast<std::uint32_t>(i);
      return next;
    });
  kept.resize(written);
  return kept;
}

template <typename Vector>
void ThreadTeam::accumulate(Vector& v, const char* phase)
{
  using Value = typename Vector::value_type;
  const std::size_t n = v.size(), parts = partsFor(n);
  std::vector<Value> before(parts + 1, Value(0)); // the sum of the stretches before each
  ThreadedWork& record = newRecord(phase);
  if (parts > 1)
  {
    run(
      parts,
      [&](std::size_t k) {
        Value sum(0);
        const Part part = partOf(n, k, parts);
        for (std::size_t i = part.first; i < part.last; ++i)
          sum += v[i];
        before[k + 1] = sum;
      },
      record);
    for (std::size_t k = 0; k < parts; ++k)
      before[k + 1] += before[k];
  }
  run(
    parts,
    [&](std::size_t k) {
      Value sum = before[k];
      const Part part = partOf(n, k, parts);
      for (std::size_t i = part.first; i < part.last; ++i)
        v[i] = sum += v[i];
    },
    record);
}

} // namespace fd3

#endif
