// A way to run a pass over [0, count) in stretches, on several threads or on one, for the code
// that should not depend on who runs it (the frame, the mesh's records).
#ifndef fd3_Stretches_h
#define fd3_Stretches_h

#include <cstddef>
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

} // namespace fd3

#endif
