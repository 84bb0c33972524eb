// The allocator of the kernel's large arrays (tetrahedra, vertices, output ids): elements are left
// uninitialized (they are written right after), and blocks are aligned to a cache line, large ones
// to 2 MB so that a system whose transparent huge pages are always on can back them with huge
// pages. Below 1 GiB they are not asked for (madvise): the first touch of each page dominates what
// pages cost, and where the host takes freed memory back a huge page's first touch costs more than
// its 4 KB pages. From 1 GiB on, the tetrahedra of large surface samples, whose thin tetrahedra
// reach across the whole set, need the reach of huge pages in the TLB more (docs/performance.md has
// the figures).
#ifndef fd3_BulkAllocator_h
#define fd3_BulkAllocator_h

#include <cstddef>
#include <new>
#include <utility>
#include <vector>

namespace fd3
{
namespace detail
{
void* allocateBulk(std::size_t bytes); ///< throws std::bad_alloc
/// Frees a block of allocateBulk(bytes); the pages of a large one go back to the system first.
void freeBulk(void* p, std::size_t bytes) noexcept;
/// Gives the whole pages within [begin, begin + bytes) back to the system (Linux; elsewhere it does
/// nothing); they read as zeros when touched again.
void releasePages(void* begin, std::size_t bytes) noexcept;
/// The system's page size: 4 KB on x86-64, 16 or 64 KB on some ARM systems.
std::size_t pageSize() noexcept;
} // namespace detail

template <typename T>
struct BulkAllocator
{
  using value_type = T;

  BulkAllocator() = default;
  template <typename U>
  BulkAllocator(const BulkAllocator<U>&) noexcept
  {}

  T* allocate(std::size_t n) { return static_cast<T*>(detail::allocateBulk(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { detail::freeBulk(p, n * sizeof(T)); }

  /// Default-initialization: no zero fill for resize().
  template <typename U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  template <typename U>
  bool operator==(const BulkAllocator<U>&) const noexcept
  {
    return true;
  }
  template <typename U>
  bool operator!=(const BulkAllocator<U>&) const noexcept
  {
    return false;
  }
};

/// Gives back the memory of `v` beyond its size without moving its elements, as a shrink_to_fit
/// would with a copy (a peak of both sizes). capacity() is unchanged.
template <typename T>
void releaseSpareCapacity(std::vector<T, BulkAllocator<T>>& v) noexcept
{
  detail::releasePages(v.data() + v.size(), (v.capacity() - v.size()) * sizeof(T));
}

} // namespace fd3

#endif
