#include "InsertionOrder.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>
#include <utility>

namespace fd3
{
namespace
{
// Curve resolution of one sorting level, and the smallest run of equal keys worth sorting again
// inside its own box (smaller runs are ordered by their coordinates).
constexpr int kHilbertBits = 10;
constexpr std::size_t kRunWorthRefining = 8;

// The 10 low bits of x moved to every third bit (bit b to bit 3b).
std::uint32_t spreadBits(std::uint32_t x)
{
  x = (x | (x << 16)) & 0x030000FFu;
  x = (x | (x << 8)) & 0x0300F00Fu;
  x = (x | (x << 4)) & 0x030C30C3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

// Skilling's transform ("Programming the Hilbert curve", 2004): coordinates of kHilbertBits bits
// -> transposed Hilbert index, whose bits interleaved from the top give the position along the
// curve. Written without branches on the data (its bits are coin tosses to the predictor).
std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z)
{
  std::uint32_t X[3] = {x, y, z};
  for (std::uint32_t q = 1u << (kHilbertBits - 1); q > 1; q >>= 1)
  {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i)
    {
      // X[i] has bit q: invert the low bits of X[0]; else exchange them between X[0] and X[i].
      const std::uint32_t has = 0u - ((X[i] & q) != 0);
      const std::uint32_t t = (X[0] ^ X[i]) & p & ~has;
      X[0] ^= t | (p & has);
      X[i] ^= t;
    }
  }
  X[1] ^= X[0];
  X[2] ^= X[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = 1u << (kHilbertBits - 1); q > 1; q >>= 1)
    t ^= (q - 1) & (0u - ((X[2] & q) != 0));
  return (spreadBits(X[0] ^ t) << 2) | (spreadBits(X[1] ^ t) << 1) | spreadBits(X[2] ^ t);
}

// Least-significant-digit radix sort of `values` by `keys` (stable), over the low `bits` bits:
// linear passes instead of std::sort's n log n comparisons.
void radixSort(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& values, int bits)
{
  constexpr int kDigit = 12;
  std::vector<std::uint64_t> keyBuffer(keys.size());
  std::vector<std::uint32_t> valueBuffer(values.size());
  std::vector<std::size_t> count(std::size_t(1) << kDigit);
  for (int shift = 0; shift < bits; shift += kDigit)
  {
    std::fill(count.begin(), count.end(), 0);
    for (std::uint64_t k : keys)
      ++count[(k >> shift) & ((1u << kDigit) - 1)];
    std::size_t offset = 0;
    for (std::size_t& c : count)
      offset += std::exchange(c, offset);
    for (std::size_t i = 0; i < keys.size(); ++i)
    {
      const std::size_t to = count[(keys[i] >> shift) & ((1u << kDigit) - 1)]++;
      keyBuffer[to] = keys[i];
      valueBuffer[to] = values[i];
    }
    keys.swap(keyBuffer);
    values.swap(valueBuffer);
  }
}

bool lexicographicallyLess(const double* xyz, std::uint32_t a, std::uint32_t b)
{
  const double* p = xyz + 3 * std::size_t(a);
  const double* q = xyz + 3 * std::size_t(b);
  return std::lexicographical_compare(p, p + 3, q, q + 3);
}

bool samePoint(const double* xyz, std::uint32_t a, std::uint32_t b)
{
  const double* p = xyz + 3 * std::size_t(a);
  const double* q = xyz + 3 * std::size_t(b);
  return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
}

/// Points in a run of equal curve keys, ordered by coordinates: equal ones side by side, in input
/// order. Marks every copy after the first as a duplicate of it (ids[i] |= kDuplicate), which only
/// such runs can hold.
constexpr std::uint32_t kDuplicate = 0x80000000u; // above any id (< 2^30)
void sortRunAndMarkDuplicates(const double* xyz, std::uint32_t* ids, std::size_t count)
{
  std::stable_sort(ids, ids + count,
    [xyz](std::uint32_t a, std::uint32_t b) { return lexicographicallyLess(xyz, a, b); });
  for (std::size_t i = 1, first = 0; i < count; ++i)
  {
    if (samePoint(xyz, ids[first], ids[i]))
      ids[i] |= kDuplicate;
    else
      first = i;
  }
}

// Sorts ids along a Hilbert curve over `box`, kHilbertBits per axis, then every run of points
// that fell into one curve cell: inside the run's own box when it is long enough (the resolution
// adapts to the points, so tight clusters, even of spread 1e-12, are ordered as well as the rest),
// else by coordinates. Every sort is stable, so equal points end up side by side, in input order;
// all but the first of them are marked kDuplicate.
void hilbertSort(const double* xyz, std::uint32_t* ids, std::size_t count, const Box& box)
{
  const double span = box.largestExtent();
  if (count < 2)
    return;
  if (!(span > 0)) // copies of one point
  {
    for (std::size_t i = 1; i < count; ++i)
      ids[i] |= kDuplicate;
    return;
  }
  const double toGrid = ((1u << kHilbertBits) - 1) / span;
  std::vector<std::uint64_t> keys(count);
  std::vector<std::uint32_t> values(ids, ids + count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* p = xyz + 3 * std::size_t(values[i]);
    std::uint32_t q[3];
    for (int a = 0; a < 3; ++a)
      q[a] = static_cast<std::uint32_t>((p[a] - box.lo[a]) * toGrid);
    keys[i] = hilbertIndex(q[0], q[1], q[2]);
  }
  radixSort(keys, values, 3 * kHilbertBits);
  std::copy(values.begin(), values.end(), ids);
  for (std::size_t begin = 0; begin < count;)
  {
    std::size_t end = begin + 1;
    while (end < count && keys[end] == keys[begin])
      ++end;
    // The extreme points of the widest axis never share a cell, so a run is shorter than count.
    if (end - begin >= kRunWorthRefining)
      hilbertSort(xyz, ids + begin, end - begin, Box::of(xyz, ids + begin, end - begin));
    else if (end - begin > 1)
      sortRunAndMarkDuplicates(xyz, ids + begin, end - begin);
    begin = end;
  }
}

/// Keeps the first of every run of equal points in `sorted` (the unmarked one) and lists the
/// others, marked by hilbertSort, as its duplicates.
void mergeDuplicates(std::vector<std::uint32_t>& sorted,
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& duplicates)
{
  std::size_t kept = 0;
  for (const std::uint32_t id : sorted)
  {
    if (id & kDuplicate)
      duplicates.emplace_back(id & ~kDuplicate, sorted[kept - 1]);
    else
      sorted[kept++] = id;
  }
  sorted.resize(kept);
}

/// BRIO rounds: round r holds about half the points of round r + 1 and the smallest goes first;
/// each round keeps the curve order of `sorted` (a stable counting sort by round). A point's round
/// comes from its key's level, which the coordinates decide: the same in every run.
std::vector<std::uint32_t> brioRounds(const std::vector<std::uint32_t>& sorted,
  const std::uint16_t* key, std::vector<std::size_t>& roundStarts)
{
  const int rounds = std::clamp(static_cast<int>(std::log2(double(sorted.size()) / 64.0)), 1, 16);
  std::vector<std::uint8_t> roundOf(sorted.size());
  std::vector<std::size_t> start(rounds + 1, 0);
  for (std::size_t i = 0; i < sorted.size(); ++i)
  {
    const int level = 15 - (key[sorted[i]] >> 12);
    roundOf[i] = static_cast<std::uint8_t>(rounds - 1 - std::min(level, rounds - 1));
    ++start[roundOf[i] + 1];
  }
  for (int r = 0; r < rounds; ++r)
    start[r + 1] += start[r];
  roundStarts.assign(start.begin(), start.end() - 1);
  std::vector<std::uint32_t> order(sorted.size());
  for (std::size_t i = 0; i < sorted.size(); ++i)
    order[start[roundOf[i]]++] = sorted[i];
  return order;
}
} // namespace

InsertionPlan planInsertion(const double* xyz, const std::uint16_t* key, std::vector<std::uint32_t> ids,
  const Box& box, InsertionOrder order, std::uint64_t seed)
{
  InsertionPlan plan;
  hilbertSort(xyz, ids.data(), ids.size(), box);
  mergeDuplicates(ids, plan.duplicates);
  std::mt19937_64 rng(seed);
  switch (order)
  {
    case InsertionOrder::Brio:
      plan.order = brioRounds(ids, key, plan.roundStarts);
      break;
    case InsertionOrder::Input:
      std::sort(ids.begin(), ids.end());
      plan.order = std::move(ids);
      plan.roundStarts = {0};
      break;
    case InsertionOrder::Random:
      std::shuffle(ids.begin(), ids.end(), rng);
      plan.order = std::move(ids);
      plan.roundStarts = {0};
      break;
  }
  return plan;
}

// A hash grid of cells of the tolerance's size: a point closer than the tolerance to a kept one has
// it in one of the 27 cells around its own. Cell coordinates saturate far from the origin, which
// only puts more points in a cell: the distances decide.
std::vector<std::pair<std::uint32_t, std::uint32_t>> skipClosePoints(
  const double* xyz, InsertionPlan& plan, double tolerance)
{
  std::vector<std::uint32_t>& order = plan.order;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> skipped;
  if (!(tolerance > 0))
    return skipped;
  auto cellOf = [tolerance](double x) {
    return static_cast<std::int64_t>(std::clamp(std::floor(x / tolerance), -0x1p40, 0x1p40));
  };
  auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return (std::uint64_t(i) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(j) * 0xC2B2AE3D27D4EB4Full) ^
      (std::uint64_t(k) * 0x165667B19E3779F9ull);
  };
  std::unordered_multimap<std::uint64_t, std::uint32_t> kept;
  kept.reserve(order.size());
  const double tolerance2 = tolerance * tolerance;
  std::size_t survivors = 0, round = 0;
  for (std::size_t position = 0; position < order.size(); ++position)
  {
    for (; round < plan.roundStarts.size() && plan.roundStarts[round] == position; ++round)
      plan.roundStarts[round] = survivors;
    const std::uint32_t id = order[position];
    const double* p = xyz + 3 * std::size_t(id);
    const std::int64_t c[3] = {cellOf(p[0]), cellOf(p[1]), cellOf(p[2])};
    std::uint32_t near = id;
    for (int d = 0; d < 27 && near == id; ++d)
    {
      const auto range = kept.equal_range(key(c[0] + d % 3 - 1, c[1] + d / 3 % 3 - 1, c[2] + d / 9 - 1));
      for (auto it = range.first; it != range.second && near == id; ++it)
      {
        const double* q = xyz + 3 * std::size_t(it->second);
        const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
        if (dx * dx + dy * dy + dz * dz < tolerance2)
          near = it->second;
      }
    }
    if (near != id)
      skipped.emplace_back(id, near);
    else
    {
      kept.emplace(key(c[0], c[1], c[2]), id);
      order[survivors++] = id;
    }
  }
  order.resize(survivors);
  return skipped;
}

} // namespace fd3
