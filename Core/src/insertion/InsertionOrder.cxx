#include "insertion/InsertionOrder.h"

#include "system/Threads.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <mutex>
#include <random>
#include <unordered_map>
#include <utility>

namespace fd3
{
namespace
{
// The smallest run of equal curve keys worth sorting again inside its own box (smaller runs are
// ordered by their coordinates).
constexpr std::size_t kRunWorthRefining = 8;
// Runs refined after the others, shared out by length.
constexpr std::size_t kLongRun = 4096;

// The kHilbertBits (10) low bits of x moved to every third bit (bit b to bit 3b).
std::uint32_t spreadBits(std::uint32_t x)
{
  x = (x | (x << 16)) & 0x030000FFu;
  x = (x | (x << 8)) & 0x0300F00Fu;
  x = (x | (x << 4)) & 0x030C30C3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

// Skilling's transform ("Programming the Hilbert curve", 2004) read as a machine that goes down
// the levels from the top: its state is what the levels above did to the bits below (a permutation
// of the axes and a flip of some) and the parity that its Gray decoding carries down. A state and
// a level's three bits give that level's three bits of the curve index and the next state. Two
// levels at a time, the index takes five lookups in a 12 KB table instead of 27 dependent steps on
// the coordinates.
class HilbertTable
{
  static_assert(kHilbertBits % 2 == 0, "the table goes two levels at a time");

public:
  constexpr HilbertTable()
  {
    for (int state = 0; state < kStates; ++state)
      for (std::uint32_t bits = 0; bits < 64; ++bits)
      {
        std::uint32_t high = 0, low = 0;
        const int middle = step(state, bits >> 3, high);
        const int next = step(middle, bits & 7u, low);
        entry_[state][bits] = static_cast<std::uint16_t>(next << 6 | high << 3 | low);
      }
  }
  // The curve index of interleaved coordinates (x at bit 3l, y at 3l+1, z at 3l+2 for level l).
  std::uint32_t index(std::uint32_t interleaved) const
  {
    std::uint32_t state = 0, index = 0;
    for (int level = kHilbertBits - 2; level >= 0; level -= 2)
    {
      const std::uint16_t e = entry_[state][(interleaved >> (3 * level)) & 63u];
      index = index << 6 | (e & 63u);
      state = e >> 6;
    }
    return index;
  }

private:
  // state = (6 * flips + permutation) * 2 + parity; the transform maps a level's bits b to
  // t[i] = b[axis[i]] ^ flip bit i.
  static constexpr int kStates = 8 * 6 * 2;
  static constexpr std::uint8_t kPermutations[6][3] = {
    {0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

  // One level: the curve's bits (axis 0 in the high bit) for the level's bits b (axis 0 in the
  // low bit, as interleaved), and the state below.
  // Written for a constant expression in C++17 (no std::swap, std::equal or uninitialised local).
  static constexpr int step(int state, std::uint32_t b, std::uint32_t& curve)
  {
    int parity = state & 1, permutation = (state >> 1) % 6, flips = (state >> 1) / 6;
    std::uint8_t axis[3] = {
      kPermutations[permutation][0], kPermutations[permutation][1], kPermutations[permutation][2]};
    int t[3] = {};
    for (int i = 0; i < 3; ++i)
      t[i] = static_cast<int>((b >> axis[i]) & 1u) ^ ((flips >> i) & 1);
    // Skilling's inner loop, on the transform of the levels below: axis i's bit set inverts axis
    // 0, clear exchanges axes 0 and i.
    for (int i = 0; i < 3; ++i)
    {
      if (t[i])
        flips ^= 1;
      else
      {
        const std::uint8_t first = axis[0];
        axis[0] = axis[i];
        axis[i] = first;
        const int differ = (flips ^ (flips >> i)) & 1;
        flips ^= differ | (differ << i);
      }
    }
    // Gray decoding: X1 ^= X0, X2 ^= X1, then every bit flipped by the parity of X2 above it.
    const int g0 = t[0], g1 = t[1] ^ g0, g2 = t[2] ^ g1;
    curve = static_cast<std::uint32_t>((g0 ^ parity) << 2 | (g1 ^ parity) << 1 | (g2 ^ parity));
    parity ^= g2;
    for (permutation = 0; permutation < 6; ++permutation) // two axes decide the third
      if (axis[0] == kPermutations[permutation][0] && axis[1] == kPermutations[permutation][1])
        break;
    return (6 * flips + permutation) * 2 + parity;
  }

  std::uint16_t entry_[kStates][64] = {};
};

// Built by the compiler: a local static's guard was tested on every point, and a table built
// before main() would read as zeros to a static constructor of a program that runs first.
constexpr HilbertTable kHilbertTable;

} // namespace

// One word per entry, not a key array and an id array, so that each pass scatters one stream.
void radixSortByHighHalf(Words& words, int bits, ThreadTeam* team)
{
  constexpr int kDigit = 10;
  constexpr std::size_t kBuckets = std::size_t(1) << kDigit;
  const std::size_t n = words.size();
  const std::size_t parts = team ? team->partsFor(n) : 1;
  ThreadedWork* record = team ? &team->newRecord("sort") : nullptr;
  const auto forParts = [&](const std::function<void(std::size_t)>& f) {
    if (team)
      team->run(parts, f, *record);
    else
      f(0);
  };
  // count[k * kBuckets + b]: part k's words with digit b; then where the next of them goes.
  std::vector<std::uint32_t> count(parts * kBuckets); // fewer than 2^32 points
  std::vector<std::uint32_t> total(kBuckets);         // each digit's words, then where they start
  Words buffer(n);
  for (int shift = 32; shift < 32 + bits; shift += kDigit)
  {
    const auto digit = [shift](std::uint64_t w) { return (w >> shift) & (kBuckets - 1); };
    forParts([&](std::size_t k) {
      std::uint32_t* mine = &count[k * kBuckets];
      std::fill(mine, mine + kBuckets, 0u);
      const Part part = partOf(n, k, parts);
      for (std::size_t i = part.first; i < part.last; ++i)
        ++mine[digit(words[i])];
    });
    // Where each part's words of each digit go: by digit, then by part (stable). Each thread sums
    // a stretch of digits over the parts, then turns them into offsets: one thread walking every
    // digit across every part's row missed the cache on each step.
    forParts([&](std::size_t k) {
      const Part digits = partOf(kBuckets, k, parts);
      for (std::size_t b = digits.first; b < digits.last; ++b)
      {
        std::uint32_t sum = 0;
        for (std::size_t j = 0; j < parts; ++j)
          sum += count[j * kBuckets + b];
        total[b] = sum;
      }
    });
    std::uint32_t start = 0;
    for (std::uint32_t& digitWords : total)
      start += std::exchange(digitWords, start);
    forParts([&](std::size_t k) {
      const Part digits = partOf(kBuckets, k, parts);
      for (std::size_t b = digits.first; b < digits.last; ++b)
      {
        std::uint32_t offset = total[b];
        for (std::size_t j = 0; j < parts; ++j)
          offset += std::exchange(count[j * kBuckets + b], offset);
      }
    });
    forParts([&](std::size_t k) {
      std::uint32_t* next = &count[k * kBuckets];
      const Part part = partOf(n, k, parts);
      for (std::size_t i = part.first; i < part.last; ++i)
        buffer[next[digit(words[i])]++] = words[i];
    });
    words.swap(buffer);
  }
  if (team)
    team->release(buffer, "sort");
}

namespace
{
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
// Levels of refinement after which a run is sorted lexicographically instead: far more than
// doubles need (each level resolves 10 bits), a bound on the recursion whatever the input.
constexpr int kMaxRefinements = 64;

/// Maps coordinates within a box onto the curve's grid, for any finite box: halves keep the
/// differences finite where the box spans more than DBL_MAX (halving is exact above the
/// subnormals, so the cells are those of (x - lo) * (2^kHilbertBits - 1) / span), and where the
/// box is so small that its scale is not a double, the scale is applied in two finite factors.
/// Halving a subnormal box can make its span 0: every point then goes to cell 0, and the run to
/// the lexicographic sort.
class GridMap
{
public:
  explicit GridMap(const Bounds& box)
  {
    double halfSpan = 0;
    for (int a = 0; a < 3; ++a)
    {
      halfLo_[a] = box.lo[a] / 2;
      halfSpan = std::max(halfSpan, box.hi[a] / 2 - halfLo_[a]);
      empty_ = empty_ && box.lo[a] == box.hi[a];
    }
    constexpr double kLastCell = (1u << kHilbertBits) - 1;
    scale_ = kLastCell / halfSpan;
    if (!std::isfinite(scale_))
    {
      int exponent = 0;
      const double mantissa = std::frexp(halfSpan, &exponent); // halfSpan = mantissa 2^exponent
      scale_ = std::ldexp(1.0, -exponent / 2);
      second_ = std::ldexp(kLastCell / mantissa, exponent / 2 - exponent);
    }
  }
  bool empty() const { return empty_; }
  std::uint32_t cell(double x, int a) const
  {
    const double c = (x / 2 - halfLo_[a]) * scale_ * second_;
    return c > 0 ? static_cast<std::uint32_t>(std::min(c, double((1u << kHilbertBits) - 1))) : 0;
  }

private:
  double halfLo_[3];
  double scale_ = 0, second_ = 1; // second_: the second factor, where one does not do
  bool empty_ = true;
};

/// Runs f(begin, end) over [0, count): on the team's threads, a stretch each, or here.
void forRanges(
  ThreadTeam* team, std::size_t count, const std::function<void(std::size_t, std::size_t)>& f)
{
  if (team)
    team->forRanges(
      count, "sort", [&](std::size_t, std::size_t begin, std::size_t end) { f(begin, end); });
  else
    f(0, count);
}

/// Calls refine(begin, end) on every run, each run on one of the team's threads: the longest
/// first, each to the thread with the fewest points so far.
void refineLongRuns(std::vector<std::pair<std::size_t, std::size_t>>& runs,
  const std::function<void(std::size_t, std::size_t)>& refine, ThreadTeam& team)
{
  if (runs.empty())
    return;
  const auto length = [](const std::pair<std::size_t, std::size_t>& run) {
    return run.second - run.first;
  };
  std::sort(runs.begin(), runs.end(), [&](const auto& a, const auto& b) {
    return length(a) != length(b) ? length(a) > length(b) : a.first < b.first;
  });
  const std::size_t parts = std::min<std::size_t>(runs.size(), std::size_t(team.size()));
  std::vector<std::vector<std::size_t>> mine(parts);
  std::vector<std::size_t> load(parts, 0);
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    const std::size_t k = std::size_t(std::min_element(load.begin(), load.end()) - load.begin());
    mine[k].push_back(r);
    load[k] += length(runs[r]);
  }
  team.run(
    parts,
    [&](std::size_t k) {
      for (const std::size_t r : mine[k])
        refine(runs[r].first, runs[r].second);
    },
    team.newRecord("sort"));
}

/// With a team at the top level: the keys, the radix sort and the runs, each thread a stretch.
/// The box of the points xyz[3 * ids[i]], i < count.
Bounds boundsOf(const double* xyz, const std::uint32_t* ids, std::size_t count)
{
  Bounds box;
  for (std::size_t i = 0; i < count; ++i)
    box.include(xyz + 3 * std::size_t(ids[i]));
  return box;
}

void hilbertSort(const double* xyz, std::uint32_t* ids, std::size_t count, const Bounds& box,
  int depth, ThreadTeam* team)
{
  if (count < 2)
    return;
  const GridMap grid(box);
  if (grid.empty()) // copies of one point
  {
    for (std::size_t i = 1; i < count; ++i)
      ids[i] |= kDuplicate;
    return;
  }
  Words entries(count); // curve key << 32 | id
  forRanges(team, count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* p = xyz + 3 * std::size_t(ids[i]);
      const std::uint32_t key =
        hilbertIndex(grid.cell(p[0], 0), grid.cell(p[1], 1), grid.cell(p[2], 2));
      entries[i] = std::uint64_t(key) << 32 | ids[i];
    }
  });
  radixSortByHighHalf(entries, 3 * kHilbertBits, team);
  const auto cell = [&](std::size_t i) { return entries[i] >> 32; };
  const auto refine = [&](std::size_t begin, std::size_t end) {
    hilbertSort(
      xyz, ids + begin, end - begin, boundsOf(xyz, ids + begin, end - begin), depth + 1, nullptr);
  };
  // Each stretch takes the runs that start in it, but for the long ones (a dense cluster's cells),
  // which are refined once all stretches are done, the longest first to the thread with the least:
  // a stretch through dense clusters had several times the work of one through sparse points.
  std::vector<std::pair<std::size_t, std::size_t>> longRuns;
  std::mutex longRunsMutex;
  forRanges(team, count, [&](std::size_t first, std::size_t last) {
    std::size_t begin = first;
    while (begin > 0 && begin < last && cell(begin) == cell(begin - 1))
      ++begin;
    while (begin < last)
    {
      std::size_t end = begin + 1;
      while (end < count && cell(end) == cell(begin))
        ++end;
      for (std::size_t i = begin; i < end; ++i)
        ids[i] = static_cast<std::uint32_t>(entries[i]);
      // The extreme points of the widest axis share no cell, so a run is shorter than count,
      // unless halving subnormal coordinates made distinct ones equal: such a run is sorted as
      // it is.
      const bool refines = end - begin < count && depth < kMaxRefinements;
      if (team && end - begin >= kLongRun && refines)
      {
        std::lock_guard<std::mutex> lock(longRunsMutex);
        longRuns.emplace_back(begin, end);
      }
      else if (end - begin >= kRunWorthRefining && refines)
        refine(begin, end);
      else if (end - begin > 1)
        sortRunAndMarkDuplicates(xyz, ids + begin, end - begin);
      begin = end;
    }
  });
  if (team)
  {
    team->release(entries, "sort");
    refineLongRuns(longRuns, refine, *team);
  }
}

/// Keeps the first of every run of equal points in `sorted` (the unmarked one) and lists the
/// others, marked by hilbertSort, as its duplicates. Each thread takes a stretch: it counts what
/// it keeps, then writes it after what the stretches before it keep.
void mergeDuplicates(IdArray& sorted,
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& duplicates, ThreadTeam& team)
{
  const std::size_t n = sorted.size();
  IdArray kept(n); // cut to those kept
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found(team.partsFor(n));
  std::size_t written = 0;
  team.countThenWrite(
    team.newRecord("sort"), 0, n, written,
    [&](std::size_t begin, std::size_t end) {
      std::size_t count = 0;
      for (std::size_t i = begin; i < end; ++i)
        count += !(sorted[i] & kDuplicate);
      return count;
    },
    [&](std::size_t k, std::size_t begin, std::size_t end, std::size_t next) {
      std::size_t original = begin; // the last unmarked one at or before i
      while (original > 0 && (sorted[original] & kDuplicate))
        --original;
      for (std::size_t i = begin; i < end; ++i)
      {
        if (sorted[i] & kDuplicate)
          found[k].emplace_back(sorted[i] & ~kDuplicate, sorted[original]);
        else
          kept[next++] = sorted[original = i];
      }
      return next;
    });
  kept.resize(written);
  for (const auto& part : found)
    duplicates.insert(duplicates.end(), part.begin(), part.end());
  sorted.swap(kept);
  team.release(kept, "sort");
}

/// BRIO rounds: round r holds about half the points of round r + 1 and the smallest goes first;
/// each round keeps the curve order of `sorted` (a stable counting sort by round). A point's round
/// comes from its key's level, which the coordinates decide: the same in every run.
IdArray brioRounds(const IdArray& sorted, const std::uint16_t* key,
  std::vector<std::size_t>& roundStarts, ThreadTeam& team)
{
  const std::size_t n = sorted.size(), parts = team.partsFor(n);
  const int rounds = std::clamp(static_cast<int>(std::log2(double(n) / 64.0)), 1, 16);
  const auto roundOf = [&](std::uint32_t id) {
    const int level = 15 - (key[id] >> 12);
    return static_cast<std::size_t>(rounds - 1 - std::min(level, rounds - 1));
  };
  // count[k * rounds + r]: stretch k's points of round r; then where the next of them goes.
  std::vector<std::size_t> count(parts * std::size_t(rounds), 0);
  ThreadedWork& record = team.newRecord("sort");
  team.run(
    parts,
    [&](std::size_t k) {
      const Part part = partOf(n, k, parts);
      for (std::size_t i = part.first; i < part.last; ++i)
        ++count[k * rounds + roundOf(sorted[i])];
    },
    record);
  roundStarts.assign(std::size_t(rounds), 0);
  std::size_t offset = 0;
  for (int r = 0; r < rounds; ++r)
  {
    roundStarts[std::size_t(r)] = offset;
    for (std::size_t k = 0; k < parts; ++k)
      offset += std::exchange(count[k * rounds + std::size_t(r)], offset);
  }
  IdArray order(n);
  team.run(
    parts,
    [&](std::size_t k) {
      const Part part = partOf(n, k, parts);
      for (std::size_t i = part.first; i < part.last; ++i)
        order[count[k * rounds + roundOf(sorted[i])]++] = sorted[i];
    },
    record);
  return order;
}
} // namespace

std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z)
{
  return kHilbertTable.index(spreadBits(x) | spreadBits(y) << 1 | spreadBits(z) << 2);
}

InsertionPlan planInsertion(const double* xyz, const std::uint16_t* key, IdArray ids,
  const Bounds& box, InsertionOrder order, std::uint64_t seed, ThreadTeam& team)
{
  InsertionPlan plan;
  hilbertSort(xyz, ids.data(), ids.size(), box, 0, &team);
  mergeDuplicates(ids, plan.duplicates, team);
  std::mt19937_64 rng(seed);
  switch (order)
  {
    case InsertionOrder::Brio:
      plan.order = brioRounds(ids, key, plan.roundStarts, team);
      team.release(ids, "sort");
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
  IdArray& order = plan.order;
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
      const auto range =
        kept.equal_range(key(c[0] + d % 3 - 1, c[1] + d / 3 % 3 - 1, c[2] + d / 9 - 1));
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
