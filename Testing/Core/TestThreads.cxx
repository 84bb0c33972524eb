// Multi-threaded insertion: the same tetrahedra for every thread count up to 64 (oversubscribed
// here), exactly valid, on every point set of the benchmark; region passes where they pay, locking
// passes where they do not; progress from the calling thread only; abort and failures stop every
// thread and leave nothing behind. The thread sanitizer build runs these too.
#include "CoreTestUtilities.h"
#include "ExactValidator.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"
#include "fd3/Workers.h"
#include "insertion/ParallelInsertion.h"
#include "system/Threads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{
fd3::Triangulation run(const fd3test::Points& p, int threads)
{
  fd3::Options options;
  options.threads = threads;
  options.pointsPerThread = 32; // region passes on 64 threads already at test sizes
  return fd3::triangulate(p.data(), p.size() / 3, options);
}

constexpr std::size_t kPoints = fd3test::kThreadTestPoints;

TEST(Threads, SameTetrahedraForEveryThreadCountOnEveryPointSet)
{
  for (const std::string& kind : fd3test::pointSetNames())
  {
    SCOPED_TRACE(kind);
    const fd3test::Points p = fd3test::generate(kind, kPoints, 4);
    const fd3::Triangulation serial = run(p, 1);
    ASSERT_EQ(serial.status, fd3::Status::Ok);
    const auto report = fd3test::checkTriangulation(p.data(), p.size() / 3, serial.tetrahedra);
    EXPECT_TRUE(report.valid()) << report.summary();
    const auto reference = fd3test::canonicalTetrahedra(serial.tetrahedra);
    std::size_t deferred = 0;
    for (int threads : {2, 3, 4, 8, 16, 64})
    {
      const fd3::Triangulation parallel = run(p, threads);
      ASSERT_EQ(parallel.status, fd3::Status::Ok) << threads << " threads";
      EXPECT_EQ(fd3test::canonicalTetrahedra(parallel.tetrahedra), reference)
        << threads << " threads";
      EXPECT_EQ(parallel.stats.insertedPoints, serial.stats.insertedPoints);
      EXPECT_EQ(parallel.stats.duplicatesMerged, serial.stats.duplicatesMerged);
      deferred += parallel.stats.deferredInsertions;
    }
    EXPECT_GT(deferred, 0u) << "the threads' borders should have put some insertions off";
  }
}

// Weighted points: the same regular tetrahedralization and hidden points for every thread count,
// where heavy points hide vertices that another region's or another locking thread's insertions
// reached: uniform radii, and a packing whose small balls inside large ones are a fifth of it.
TEST(Threads, SameRegularTetrahedraForEveryThreadCount)
{
  const std::size_t n = kPoints;
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> unit(0, 1);
  fd3test::Points uniform = fd3test::uniformCube(n, 6), packing = uniform;
  std::vector<double> radii(n), packed(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    radii[i] = 0.002 + 0.02 * unit(random);
    packed[i] = 0.03;
    if (i % 5 == 4) // beside the point before it, far smaller
    {
      for (int k = 0; k < 3; ++k)
        packing[3 * i + k] = packing[3 * (i - 1) + k] + 0.002 * unit(random);
      packed[i] = 0.001;
    }
  }
  for (auto [p, r] : {std::pair(&uniform, &radii), std::pair(&packing, &packed)})
  {
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i)
      w[i] = (*r)[i] * (*r)[i];
    fd3::Options options;
    options.pointsPerThread = 32;
    const fd3::Triangulation serial = fd3::triangulate(p->data(), w.data(), n, options);
    ASSERT_EQ(serial.status, fd3::Status::Ok);
    EXPECT_GT(serial.hidden.size(), 0u);
    fd3test::ValidityOptions check;
    check.weights = w.data();
    check.hidden = serial.hidden;
    const auto report = fd3test::checkTriangulation(p->data(), n, serial.tetrahedra, check);
    EXPECT_TRUE(report.valid()) << report.summary();
    const auto reference = fd3test::canonicalTetrahedra(serial.tetrahedra);
    std::size_t deferred = 0;
    for (int threads : {2, 3, 8, 64})
    {
      options.threads = threads;
      const fd3::Triangulation parallel = fd3::triangulate(p->data(), w.data(), n, options);
      ASSERT_EQ(parallel.status, fd3::Status::Ok) << threads << " threads";
      EXPECT_EQ(fd3test::canonicalTetrahedra(parallel.tetrahedra), reference)
        << threads << " threads";
      EXPECT_EQ(parallel.hidden, serial.hidden) << threads << " threads";
      EXPECT_EQ(parallel.stats.insertedPoints, serial.stats.insertedPoints);
      EXPECT_EQ(parallel.stats.hiddenPoints, serial.stats.hiddenPoints);
      deferred += parallel.stats.deferredInsertions;
    }
    EXPECT_GT(deferred, 0u) << "the threads' borders should have put some insertions off";
  }
}

// A thread's share of a round, in the whole set's curve order, leaves its region and comes back in
// elsewhere; on a surface sample the curve also jumps across empty space. Walks from the thread's
// last tetrahedron alone then crossed the region: a torus of 100k points took up to 2,583 steps on
// 2 threads, 70 on one. Here (40k points) it took up to 365 and 668 steps on 2 and 4 threads, now
// 55 and 104 (a start from the grid's vertex of the region); issue 10 bounds every walk by 500.
TEST(Threads, WalksInARegionStartNearThePoint)
{
  const fd3test::Points p = fd3test::torusSurface(kPoints, 4);
  for (int threads : {2, 4})
  {
    const fd3::Triangulation parallel = run(p, threads);
    ASSERT_EQ(parallel.status, fd3::Status::Ok);
    EXPECT_LE(parallel.stats.maxWalkSteps, 500u) << threads << " threads";
  }
}

/// The points each kind of insertion pass put in, summed over the rounds.
std::size_t insertedBy(const fd3::Triangulation& r, const std::string& phase)
{
  std::size_t inserted = 0;
  for (const fd3::ThreadedWork& w : r.threadedWork)
    if (std::string(w.phase).rfind(phase, 0) == 0)
      inserted += w.points - w.left;
  return inserted;
}

// Points on a cylinder all lie on its hull, whose faces run its whole length, and its inner
// tetrahedra span its width: nearly every insertion reaches outside any region. A region pass that
// puts off most of its points must stop being tried (before, each point was put off twice: 78,488
// times for 40,000 points), and the locking passes insert them instead. Uniform points go in
// regions mostly, the locking passes taking what lies near the regions' borders.
TEST(Threads, RegionPassesWhereTheyPayLockingPassesElsewhere)
{
  const fd3test::Points p = fd3test::cylinderSurface(kPoints, 4);
  const fd3::Triangulation cylinder = run(p, 2);
  ASSERT_EQ(cylinder.status, fd3::Status::Ok);
  EXPECT_LT(cylinder.stats.deferredInsertions, kPoints / 2);
  EXPECT_GT(insertedBy(cylinder, "insertion locking"), kPoints / 2);
  EXPECT_LT(insertedBy(cylinder, "insertion region"), kPoints / 10);
  const fd3::Triangulation cube = run(fd3test::uniformCube(kPoints, 4), 2);
  EXPECT_GT(insertedBy(cube, "insertion region"), kPoints / 2);
  EXPECT_GT(insertedBy(cube, "insertion locking"), 0u);
}

// A region pass gives each thread a region of pointsPerThread points at least; a smaller round goes
// to the locking passes whole, on every thread. Before, such a round was cut into fewer regions
// than threads, and each took a region's share of the round, several times what the locking pass
// on every thread takes.
TEST(Threads, RegionPassesGiveEveryThreadARegionOfPointsPerThread)
{
  fd3::Options options;
  options.threads = 4;
  options.pointsPerThread = 512;
  const fd3test::Points p = fd3test::uniformCube(kPoints, 6);
  const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3, options);
  ASSERT_EQ(r.status, fd3::Status::Ok);
  const std::size_t least = 4 * options.pointsPerThread;
  std::size_t regionPasses = 0, roundsLocked = 0;
  bool afterRegionPass = false;
  for (const fd3::ThreadedWork& w : r.threadedWork)
  {
    const std::string phase = w.phase;
    if (phase.rfind("insertion region", 0) == 0)
    {
      ++regionPasses;
      EXPECT_GE(w.points, least);
      EXPECT_EQ(w.threadSeconds.size(), 4u);
    }
    else if (phase == "insertion locking pass 1" && !afterRegionPass)
    {
      ++roundsLocked; // a whole round
      EXPECT_LT(w.points, least);
    }
    if (phase.rfind("insertion", 0) == 0)
      afterRegionPass = phase.rfind("insertion region", 0) == 0;
  }
  EXPECT_GT(regionPasses, 0u);
  EXPECT_GT(roundsLocked, 0u);
}

// Every stretch of threaded work names its phase and each of its threads' CPU time, and the
// insertion passes' points add up: no pass puts in more than it was given, and no thread stands
// for more than the team's.
TEST(Threads, ThreadedWorkIsRecorded)
{
  const fd3test::Points p = fd3test::uniformCube(kPoints, 5);
  const fd3::Triangulation r = run(p, 4);
  ASSERT_EQ(r.status, fd3::Status::Ok);
  ASSERT_FALSE(r.threadedWork.empty());
  for (const fd3::ThreadedWork& w : r.threadedWork)
  {
    EXPECT_GT(std::string(w.phase).size(), 0u);
    EXPECT_GE(w.threadSeconds.size(), 1u);
    EXPECT_LE(w.threadSeconds.size(), 4u);
    EXPECT_LE(w.left, w.points);
    for (const double seconds : w.threadSeconds)
      EXPECT_GE(seconds, 0.0);
  }
  EXPECT_LE(insertedBy(r, "insertion"), r.stats.insertedPoints);
  for (const char* phase : {"sort", "output", "insertion region", "insertion locking"})
    EXPECT_TRUE(std::any_of(r.threadedWork.begin(), r.threadedWork.end(),
      [&](const fd3::ThreadedWork& w) { return std::string(w.phase).rfind(phase, 0) == 0; }))
      << phase;
}

// A run wakes only the helpers it needs, each woken by its parent in a tree: every part runs once,
// on its own thread, for every number of parts, in any order of runs.
TEST(Threads, EveryPartRunsOnceOnItsOwnThreadForEveryCount)
{
  fd3::ThreadTeam team(64);
  for (const std::size_t parts : {64, 1, 2, 3, 7, 64, 33, 5, 64, 16, 2})
  {
    SCOPED_TRACE(parts);
    std::vector<std::atomic<int>> runs(parts);
    std::vector<std::thread::id> ids(parts);
    fd3::ThreadedWork& record = team.newRecord("test");
    team.run(
      parts,
      [&](std::size_t k) {
        ++runs[k];
        ids[k] = std::this_thread::get_id();
      },
      record);
    EXPECT_TRUE(std::all_of(runs.begin(), runs.end(), [](const auto& n) { return n == 1; }));
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(std::unique(ids.begin(), ids.end()), ids.end()) << "two parts shared a thread";
    EXPECT_EQ(record.threadSeconds.size(), parts);
  }
}

// The callers' loops (fd3::Workers): every index of [0, count) once, in contiguous ranges, on
// several threads where there is enough work, and a range's exception rethrown on the caller.
TEST(Threads, WorkersCoverEveryIndexOnceAndRethrow)
{
  for (const int threads : {1, 3, 64})
  {
    fd3::Workers workers(threads);
    EXPECT_EQ(workers.size(), threads);
    for (const std::size_t count : {0, 1, 4095, 100000})
    {
      SCOPED_TRACE(std::to_string(threads) + " threads, " + std::to_string(count));
      std::vector<std::atomic<int>> visits(count);
      std::vector<std::thread::id> ids;
      std::mutex idsMutex;
      workers.forRanges(count, [&](std::size_t begin, std::size_t end) {
        ASSERT_LE(begin, end);
        for (std::size_t i = begin; i < end; ++i)
          ++visits[i];
        const std::lock_guard<std::mutex> lock(idsMutex);
        ids.push_back(std::this_thread::get_id());
      });
      EXPECT_TRUE(std::all_of(visits.begin(), visits.end(), [](const auto& n) { return n == 1; }));
      std::sort(ids.begin(), ids.end());
      EXPECT_EQ(std::unique(ids.begin(), ids.end()), ids.end()) << "two ranges shared a thread";
      if (count == 100000)
        EXPECT_EQ(ids.size(), std::size_t(std::min(threads, 24)));
    }
    EXPECT_THROW(workers.forRanges(100000,
                   [](std::size_t, std::size_t end) {
                     if (end == 100000)
                       throw std::runtime_error("the last range failed");
                   }),
      std::runtime_error);
  }
}

// A locking pass's stretches: every rank is handed out once, however the threads race to split
// each other's; a thread slowed down by costly points (a costly stretch of the curve) has the far
// part of its stretch taken by the others; a stretch whose thread has not started is left to it.
TEST(Threads, SharedStretchesHandOutEveryRankOnceAndSplitTheSlowest)
{
  for (const std::size_t threads : {2, 16, 64})
  {
    SCOPED_TRACE(threads);
    const std::size_t count = 20000;
    fd3::SharedStretches stretches(count, threads);
    std::vector<std::atomic<int>> taken(count);
    std::vector<std::size_t> mine(threads, 0);
    // Thread 0's points cost CPU time (not a wait for a core). The others start once it has had
    // more CPU time than they will need for their own stretches, whatever the machine's load, so
    // that its stretch is theirs to split; they wait asleep, which costs them none. Its points
    // go on costing until another thread has taken part of its stretch: where threads far
    // outnumber the cores, it could finish its stretch before the others had run at all.
    const auto burn = [](double seconds) {
      for (const double start = fd3::threadCpuSeconds(); fd3::threadCpuSeconds() < start + seconds;)
        ;
    };
    std::atomic<bool> go{false}, split{false};
    double giveUp = 0; // thread 0's
    std::vector<std::thread> team;
    for (std::size_t k = 0; k < threads; ++k)
      team.emplace_back([&, k] {
        std::size_t rank = 0;
        while (k > 0 && !go)
          std::this_thread::sleep_for(std::chrono::microseconds(200));
        while (stretches.next(k, rank))
        {
          ++taken[rank];
          mine[k] += rank >= count * k / threads && rank < count * (k + 1) / threads;
          if (k > 0 && rank < count / threads)
            split = true;
          if (k == 0)
          {
            if (!go)
            {
              burn(0.2);
              go = true;
              giveUp = fd3::threadCpuSeconds() + 5.0;
            }
            do
              burn(50e-6);
            while (!split && fd3::threadCpuSeconds() < giveUp);
          }
        }
      });
    for (std::thread& t : team)
      t.join();
    EXPECT_TRUE(std::all_of(taken.begin(), taken.end(), [](const auto& n) { return n == 1; }));
    EXPECT_LT(mine[0], count / threads) << "the slow thread's stretch was not split";
  }
  fd3::SharedStretches waiting(1000, 2);
  std::size_t rank = 0, handedOut = 0;
  while (waiting.next(1, rank))
  {
    EXPECT_GE(rank, 500u) << "a stretch whose thread had not started was split";
    ++handedOut;
  }
  EXPECT_EQ(handedOut, 500u);
  const auto rest = waiting.takeRest(0);
  EXPECT_EQ(rest.first, 0u);
  EXPECT_EQ(rest.second, 500u);
}

TEST(Threads, ProgressComesFromTheCallingThreadOnly)
{
  const fd3test::Points p = fd3test::uniformCube(60000, 8);
  fd3::Options options;
  options.threads = 3;
  options.pointsPerThread = 256;
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> calls{0}, foreign{0};
  options.progress = [&](double) {
    ++calls;
    foreign += std::this_thread::get_id() != caller;
    return true;
  };
  const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3, options);
  ASSERT_EQ(r.status, fd3::Status::Ok);
  EXPECT_GT(calls, 0);
  EXPECT_EQ(foreign, 0);
}

TEST(Threads, AbortStopsEveryThread)
{
  const fd3test::Points p = fd3test::uniformCube(60000, 9);
  fd3::Options options;
  options.threads = 4;
  options.pointsPerThread = 256;
  int calls = 0;
  options.progress = [&](double fraction) { return ++calls < 2 || fraction < 0.3; };
  const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3, options);
  EXPECT_EQ(r.status, fd3::Status::Aborted);
  EXPECT_TRUE(r.tetrahedra.empty());
  // And the next run is whole.
  options.progress = nullptr;
  const fd3::Triangulation again = fd3::triangulate(p.data(), p.size() / 3, options);
  EXPECT_EQ(again.status, fd3::Status::Ok);
  EXPECT_EQ(again.stats.insertedPoints, 60000u);
}

TEST(Threads, FailureInTheCallbackCrossesAndReleasesEverything)
{
  const fd3test::Points p = fd3test::uniformCube(60000, 10);
  fd3::Options options;
  options.threads = 2;
  options.pointsPerThread = 256;
  options.progress = [](double fraction) -> bool {
    if (fraction > 0.4)
      throw std::runtime_error("simulated failure");
    return true;
  };
  EXPECT_THROW(fd3::triangulate(p.data(), p.size() / 3, options), std::runtime_error);
}

TEST(Threads, AllHardwareThreadsByDefaultOfZero)
{
  const fd3test::Points p = fd3test::lattice(20);
  fd3::Options options;
  options.threads = 0;
  options.pointsPerThread = 64;
  const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3, options);
  ASSERT_EQ(r.status, fd3::Status::Ok);
  const auto report = fd3test::checkTriangulation(p.data(), p.size() / 3, r.tetrahedra);
  EXPECT_TRUE(report.valid()) << report.summary();
}

} // namespace
