#include "fd3/Workers.h"

#include "system/Threads.h"

namespace fd3
{

Workers::Workers(int threads) : team_(std::make_unique<ThreadTeam>(boundedThreads(threads))) {}

Workers::~Workers() = default;

int Workers::size() const
{
  return team_->size();
}

void Workers::forRanges(
  std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  team_->forRanges(
    count, "workers", [&](std::size_t, std::size_t begin, std::size_t end) { body(begin, end); });
}

} // namespace fd3
