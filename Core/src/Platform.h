// The compiler-specific operations the kernel uses, each with a portable fallback. Defining
// FD3_PORTABLE (CMake option FD3_PORTABLE, built and tested by ./setup.sh test) forces the
// fallbacks, so that they stay correct on compilers where they are the only choice.
#ifndef fd3_Platform_h
#define fd3_Platform_h

#include <cstdint>

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

} // namespace fd3

#endif
