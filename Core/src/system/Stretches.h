// A way to run a pass over [0, count) in stretches, on several threads or on one, for the code
// that should not depend on who runs it (the frame, the mesh's records).
#ifndef fd3_Stretches_h
#define fd3_Stretches_h

#include "fd3/BulkAllocator.h"

#include <cstddef>
#include <cstdint>
#include <functional>

namespace fd3
{

/// Runs f(begin, end) on stretches that cover [0, count), in any order, at once or one by one.
using Stretches =
  std::function<void(std::size_t count, const std::function<void(std::size_t, std::size_t)>& f)>;

/// f over [0, count) by `stretches`, or in one stretch here when there are none.
inline void forStretches(const Stretches& stretches, std::size_t count,
  const std::function<void(std::size_t, std::size_t)>& f)
{
  if (stretches)
    stretches(count, f);
  else
    f(0, count);
}

/// Gives the whole pages of [begin, begin + bytes) back to the system (detail::releasePages), a
/// stretch of pages at a time by `stretches`: free() would do the kernel's work per page on one
/// thread. The stretches are of sixteenths of a page, each page released by the stretch where it
/// begins: the kernel's work for a page is that of many items of other work, and stretches sized
/// for items left a block of 16 MB to one thread.
inline void releasePages(const Stretches& stretches, void* begin, std::size_t bytes)
{
  constexpr std::size_t kPerPage = 16;
  const std::uintptr_t page = detail::pageSize();
  const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(begin) + page - 1) / page * page;
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(begin) + bytes) / page * page;
  if (first < end)
    forStretches(stretches, (end - first) / page * kPerPage, [&](std::size_t from, std::size_t to) {
      const std::size_t pageFrom = (from + kPerPage - 1) / kPerPage;
      const std::size_t pageTo = (to + kPerPage - 1) / kPerPage;
      if (pageFrom < pageTo)
        detail::releasePages(
          reinterpret_cast<void*>(first + pageFrom * page), (pageTo - pageFrom) * page);
    });
}

} // namespace fd3

#endif
