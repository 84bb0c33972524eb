// The compiler-specific operations the kernel uses, each with a portable fallback. Defining
// FD3_PORTABLE (CMake option FD3_PORTABLE, built and tested by ./setup.sh sanitizers) forces the
// fallbacks, so that they stay correct on compilers where they are the only choice.
#ifndef fd3_Platform_h
#define fd3_Platform_h

#include <chrono>
#include <cstdint>

#if !defined(FD3_PORTABLE) && (defined(__unix__) || defined(__APPLE__))
#include <time.h>
#define FD3_HAVE_THREAD_CLOCK 1
#endif
#if !defined(FD3_PORTABLE) && defined(__linux__)
#include <pthread.h>
#define FD3_HAVE_OTHER_THREADS_CLOCKS 1
#endif
#if !defined(FD3_PORTABLE) && defined(_MSC_VER)
#include <intrin.h>
#endif

// A signed 128-bit integer type: the exact stage of the predicates on integer grids uses it, and
// falls back to expansion arithmetic where there is none.
#if !defined(FD3_PORTABLE) && defined(__SIZEOF_INT128__)
#define FD3_HAVE_INT128 1
#endif

namespace fd3
{

/// Index of the lowest set bit of x, which must not be 0.
inline int countTrailingZeros(std::uint64_t x)
{
#if !defined(FD3_PORTABLE) && (defined(__GNUC__) || defined(__clang__))
  return __builtin_ctzll(x);
#elif !defined(FD3_PORTABLE) && defined(_MSC_VER) && defined(_M_X64)
  unsigned long index;
  _BitScanForward64(&index, x);
  return static_cast<int>(index);
#else
  int n = 0;
  for (; !(x & 1u); x >>= 1)
    ++n;
  return n;
#endif
}

/// Starts loading the cache line at p, which the caller will need soon. A hint: the fallback
/// does nothing.
inline void prefetch(const void* p)
{
#if !defined(FD3_PORTABLE) && (defined(__GNUC__) || defined(__clang__))
  __builtin_prefetch(p);
#elif !defined(FD3_PORTABLE) && defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
  _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0);
#else
  (void)p;
#endif
}

/// A load and a store of a word that another thread may write or read at the same time (a
/// vertex's tetrahedron during a locking pass): atomic, with no ordering. The fallback is a plain
/// access, which aligned 32-bit words get on every processor the kernel runs on.
inline std::uint32_t relaxedLoad(const std::uint32_t& word)
{
#if !defined(FD3_PORTABLE) && (defined(__GNUC__) || defined(__clang__))
  return __atomic_load_n(&word, __ATOMIC_RELAXED);
#else
  return *static_cast<const volatile std::uint32_t*>(&word);
#endif
}
inline void relaxedStore(std::uint32_t& word, std::uint32_t value)
{
#if !defined(FD3_PORTABLE) && (defined(__GNUC__) || defined(__clang__))
  __atomic_store_n(&word, value, __ATOMIC_RELAXED);
#else
  *static_cast<volatile std::uint32_t*>(&word) = value;
#endif
}

/// CPU seconds the calling thread has used (its own clock, for the scaling model of the threaded
/// work). The fallback is wall-clock time, which counts a thread's waits as well.
inline double threadCpuSeconds()
{
#if defined(FD3_HAVE_THREAD_CLOCK)
  timespec now;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
#else
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
#endif
}

/// The CPU-time clock of a thread, which any thread of the process may read (Linux). Elsewhere it
/// reads wall-clock time, as if every thread had a core of its own.
class ThreadCpuClock
{
public:
  /// The calling thread's.
  static ThreadCpuClock ofThisThread()
  {
    ThreadCpuClock clock;
#if defined(FD3_HAVE_OTHER_THREADS_CLOCKS)
    if (pthread_getcpuclockid(pthread_self(), &clock.id_) != 0)
      clock.id_ = CLOCK_MONOTONIC;
#endif
    return clock;
  }
  double seconds() const
  {
#if defined(FD3_HAVE_OTHER_THREADS_CLOCKS)
    timespec now;
    clock_gettime(id_, &now);
    return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
#else
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
#endif
  }

private:
#if defined(FD3_HAVE_OTHER_THREADS_CLOCKS)
  clockid_t id_ = CLOCK_MONOTONIC;
#endif
};

} // namespace fd3

#endif
