// Threads for loops of the kernel's callers: the VTK filters write their output on them. VTK's own
// SMP tools would do it where VTK was built with a threaded backend, but ParaView's packages use
// the sequential one, which left the conversion of a million Voronoi polyhedra on one thread
// while the kernel ran on all of them.
#ifndef fd3_Workers_h
#define fd3_Workers_h

#include <cstddef>
#include <functional>
#include <memory>

namespace fd3
{
class ThreadTeam;

/// A team of threads, started once, for loops over contiguous ranges.
class Workers
{
public:
  /// `threads` as Options::threads: 0 for every hardware thread, at most
  /// kThreadsPerHardwareThread per hardware thread (or kMinThreadLimit) started.
  explicit Workers(int threads);
  Workers(const Workers&) = delete;
  Workers& operator=(const Workers&) = delete;
  ~Workers();

  int size() const;
  /// Runs body(begin, end) on contiguous ranges that cover [0, count), one per thread (fewer when
  /// count is small), the calling thread taking the first; returns when every range is done, then
  /// rethrows the first exception of a range.
  void forRanges(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body);

private:
  std::unique_ptr<ThreadTeam> team_;
};

} // namespace fd3

#endif
