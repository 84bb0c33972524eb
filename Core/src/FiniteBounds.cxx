#include "FiniteBounds.h"

#include <vector>

namespace fd3
{

Bounds finiteBounds(
  ThreadTeam& team, const char* phase, const double* xyz, std::size_t count, IdArray* finiteIds)
{
  std::vector<Bounds> stretch(team.partsFor(count)); // each thread's own
  const auto finite = [xyz](std::size_t i) { return isFinite(xyz + 3 * i); };
  if (!finiteIds)
    team.forRanges(count, phase, [&](std::size_t k, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        if (finite(i))
          stretch[k].include(xyz + 3 * i);
    });
  else
  {
    IdArray& ids = *finiteIds;
    ids.resize(count); // as many as can be finite; cut to those that are
    std::size_t written = 0;
    team.countThenWrite(
      team.newRecord(phase), 0, count, written,
      [&](std::size_t begin, std::size_t end) {
        std::size_t n = 0;
        for (std::size_t i = begin; i < end; ++i)
          n += finite(i);
        return n;
      },
      [&](std::size_t k, std::size_t begin, std::size_t end, std::size_t next) {
        for (std::size_t i = begin; i < end; ++i)
          if (finite(i))
          {
            stretch[k].include(xyz + 3 * i);
            ids[next++] = static_cast<std::uint32_t>(i);
          }
        return next;
      });
    ids.resize(written);
  }
  Bounds all;
  for (const Bounds& b : stretch)
    all.include(b);
  return all;
}

Bounds finiteBounds(const double* xyz, std::size_t count, int threads)
{
  ThreadTeam team(boundedThreads(threads));
  return finiteBounds(team, "finite bounds", xyz, count);
}

} // namespace fd3
