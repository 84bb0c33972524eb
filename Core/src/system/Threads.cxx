#include "system/Threads.h"

#include "system/Platform.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <system_error>

namespace fd3
{

int boundedThreads(int requested)
{
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (requested <= 0)
    return hardware;
  return std::min(requested, std::max(kThreadsPerHardwareThread * hardware, kMinThreadLimit));
}

ThreadTeam::ThreadTeam(int size) : size_(std::max(size, 1)) {}

ThreadTeam::~ThreadTeam()
{
  for (std::size_t k = 0; k < helpers_.size(); ++k)
  {
    Seat& seat = seats_[k];
    {
      std::lock_guard<std::mutex> lock(seat.mutex);
      seat.quit = true;
    }
    seat.wake.notify_one();
  }
  for (std::thread& helper : helpers_)
    helper.join();
}

void ThreadTeam::startHelpers()
{
  started_ = true;
  seats_ = std::make_unique<Seat[]>(std::size_t(size_ - 1));
  for (int k = 1; k < size_; ++k)
  {
    try
    {
      helpers_.emplace_back(&ThreadTeam::serve, this, std::size_t(k));
    }
    catch (const std::system_error&)
    {
      return; // the calling thread runs the parts of the threads that could not start
    }
  }
}

void ThreadTeam::wakeChildren(std::size_t k)
{
  for (std::size_t child = std::max<std::size_t>(2 * k, 1); child <= 2 * k + 1; ++child)
  {
    if (child > onHelpers_)
      return;
    Seat& seat = seats_[child - 1];
    {
      std::lock_guard<std::mutex> lock(seat.mutex);
      ++seat.generation;
    }
    seat.wake.notify_one();
  }
}

void ThreadTeam::runPart(std::size_t k)
{
  const double start = threadCpuSeconds();
  try
  {
    (*part_)(k);
  }
  catch (...)
  {
    failures_[k] = std::current_exception();
  }
  // Each part writes its own element: no two threads write one.
  record_->threadSeconds[k] += threadCpuSeconds() - start;
}

void ThreadTeam::serve(std::size_t k)
{
  Seat& seat = seats_[k - 1];
  std::size_t seen = 0;
  for (;;)
  {
    {
      std::unique_lock<std::mutex> lock(seat.mutex);
      seat.wake.wait(lock, [&] { return seat.quit || seat.generation != seen; });
      if (seat.quit)
        return;
      seen = seat.generation;
    }
    wakeChildren(k);
    runPart(k);
    std::lock_guard<std::mutex> lock(mutex_);
    if (++finished_ == parts_)
      done_.notify_one();
  }
}

void ThreadTeam::run(std::size_t parts, const std::function<void(std::size_t)>& part,
  ThreadedWork& record, const std::function<void()>& poll)
{
  parts = std::min(std::max<std::size_t>(parts, 1), std::size_t(size_));
  if (!started_ && parts > 1)
    startHelpers();
  record.threadSeconds.resize(std::max(record.threadSeconds.size(), parts), 0.0);
  const std::size_t onHelpers = std::min(parts - 1, helpers_.size());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    part_ = &part;
    record_ = &record;
    failures_.assign(parts + 1, nullptr);
    parts_ = onHelpers + 1; // the parts the helpers run, and the calling thread's own
    onHelpers_ = onHelpers;
    finished_ = 1;
  }
  wakeChildren(0);
  const double start = threadCpuSeconds();
  runPart(0);
  for (std::size_t k = onHelpers + 1; k < parts; ++k)
    runPart(k);
  record.callerSeconds += threadCpuSeconds() - start;
  std::unique_lock<std::mutex> lock(mutex_);
  while (finished_ < parts_)
  {
    if (!poll || failures_[parts])
    {
      done_.wait(lock, [&] { return finished_ == parts_; });
      break;
    }
    done_.wait_for(lock, std::chrono::milliseconds(5));
    lock.unlock();
    try
    {
      poll();
    }
    catch (...)
    {
      failures_[parts] = std::current_exception();
    }
    lock.lock();
  }
  for (const std::exception_ptr& failure : failures_)
    if (failure)
      std::rethrow_exception(failure);
}

ThreadedWork& ThreadTeam::newRecord(const char* phase)
{
  records_.emplace_back();
  records_.back().phase = phase;
  return records_.back();
}

std::size_t ThreadTeam::partsFor(std::size_t count) const
{
  return std::max<std::size_t>(1, std::min<std::size_t>(size_, count / kMinItemsPerPart));
}

void ThreadTeam::forRanges(std::size_t count, const char* phase,
  const std::function<void(std::size_t, std::size_t, std::size_t)>& f)
{
  const std::size_t parts = partsFor(count);
  run(
    parts,
    [&](std::size_t k) {
      const Part part = partOf(count, k, parts);
      f(k, part.first, part.last);
    },
    newRecord(phase));
}

void ThreadTeam::releasePages(void* begin, std::size_t bytes, const char* phase)
{
  fd3::releasePages(stretches(phase), begin, bytes);
}

Stretches ThreadTeam::stretches(const char* phase)
{
  return [this, phase](std::size_t count, const std::function<void(std::size_t, std::size_t)>& f) {
    forRanges(
      count, phase, [&](std::size_t, std::size_t begin, std::size_t end) { f(begin, end); });
  };
}

} // namespace fd3
