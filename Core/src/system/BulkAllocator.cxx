#include "fd3/BulkAllocator.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#if defined(_WIN32)
#include <malloc.h>
#elif defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace fd3
{
namespace detail
{
namespace
{
constexpr std::size_t kHugePage = std::size_t(1) << 21;
// Smaller blocks are aligned to a cache line: malloc() promises 16 bytes, which is less than the
// 32 of a Vertex (alignas) and would split records across cache lines.
constexpr std::size_t kCacheLine = 64;
// Below this, alignment to huge pages would waste more than it saves.
constexpr std::size_t kLarge = 4 * kHugePage;
// From this size on, huge pages are asked for: the tetrahedra of large surface samples, whose
// thin tetrahedra reach across the whole set, need their reach in the TLB more than the first
// touch costs (BulkAllocator.h).
constexpr std::size_t kHugePagesWorth = std::size_t(1) << 30;
} // namespace

void* allocateBulk(std::size_t bytes)
{
  void* p = nullptr;
#if defined(_WIN32)
  p = _aligned_malloc(bytes > 0 ? bytes : 1, 64);
#else
  if (bytes >= kLarge)
  {
    p = std::aligned_alloc(kHugePage, (bytes + kHugePage - 1) / kHugePage * kHugePage);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Only the whole huge pages within the request: a huge page at the tail would make resident up
    // to 2 MB that no element uses.
    if (p && bytes >= kHugePagesWorth)
      madvise(p, bytes / kHugePage * kHugePage, MADV_HUGEPAGE);
#endif
  }
  else
    p = std::aligned_alloc(
      kCacheLine, (std::max<std::size_t>(bytes, 1) + kCacheLine - 1) / kCacheLine * kCacheLine);
#endif
  if (!p)
    throw std::bad_alloc();
  return p;
}

std::size_t pageSize() noexcept
{
#if defined(__linux__)
  static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return page;
#else
  return 4096;
#endif
}

void releasePages(void* begin, std::size_t bytes) noexcept
{
#if defined(__linux__)
  // madvise needs a page-aligned start.
  const std::uintptr_t page = pageSize();
  const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) & ~(page - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(begin) + bytes) & ~(page - 1);
  if (first < end)
    madvise(reinterpret_cast<void*>(first), end - first, MADV_DONTNEED);
#else
  (void)begin;
  (void)bytes;
#endif
}

void freeBulk(void* p, std::size_t bytes) noexcept
{
#if defined(_WIN32)
  (void)bytes;
  _aligned_free(p);
#else
  // A large block is not always a mapping of its own that free() unmaps: glibc serves it from a
  // free region of its heap when one is large enough (a process that freed many small blocks
  // before, as a long ParaView session has), and then keeps its pages resident after free(): the
  // first reserve of the tetrahedra, replaced at n/32 points, would stay on top of the mesh.
  if (p && bytes >= kLarge)
    releasePages(p, bytes);
  std::free(p);
#endif
}

} // namespace detail
} // namespace fd3
