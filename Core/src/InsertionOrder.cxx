#include "InsertionOrder.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

namespace fd3
{

// Skilling's transform ("Programming the Hilbert curve", 2004): coordinates -> transposed Hilbert
// index, whose bits interleaved from the top give the position along the curve.
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits)
{
  std::uint32_t X[3] = {x, y, z};
  const std::uint32_t top = 1u << (bits - 1);
  for (std::uint32_t q = top; q > 1; q >>= 1)
  {
    const std::uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i)
    {
      if (X[i] & q)
        X[0] ^= p;
      else
      {
        const std::uint32_t t = (X[0] ^ X[i]) & p;
        X[0] ^= t;
        X[i] ^= t;
      }
    }
  }
  X[1] ^= X[0];
  X[2] ^= X[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = top; q > 1; q >>= 1)
    if (X[2] & q)
      t ^= q - 1;
  for (auto& c : X)
    c ^= t;
  std::uint64_t key = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (int i = 0; i < 3; ++i)
      key = (key << 1) | ((X[i] >> b) & 1u);
  return key;
}

std::vector<std::uint32_t> insertionOrder(const double* xyz, std::vector<std::uint32_t> ids,
  InsertionOrder order, std::uint64_t seed)
{
  if (order == InsertionOrder::Input)
    return ids;
  std::mt19937_64 rng(seed);
  if (order == InsertionOrder::Random)
  {
    std::shuffle(ids.begin(), ids.end(), rng);
    return ids;
  }
  if (ids.empty())
    return ids;

  // BRIO rounds: round r holds about half the points of round r + 1; the smallest goes first.
  const int rounds = std::clamp(static_cast<int>(std::log2(double(ids.size()) / 64.0)), 1, 63);
  std::vector<std::uint64_t> keys(ids.size());
  for (std::uint64_t& key : keys)
  {
    const int laterRoundsSkipped =
      std::min(static_cast<int>(__builtin_ctzll(rng() | (1ull << 62))), rounds - 1);
    key = static_cast<std::uint64_t>(rounds - 1 - laterRoundsSkipped);
  }
  radixSort(keys, ids, 6);
  for (std::size_t begin = 0; begin < ids.size();)
  {
    std::size_t end = begin;
    while (end < ids.size() && keys[end] == keys[begin])
      ++end;
    hilbertSort(xyz, ids.data() + begin, end - begin);
    begin = end;
  }
  return ids;
}

// Sorts ids along a Hilbert curve over their bounding box, 10 bits per axis, then sorts again
// every run of points that fell into one curve cell, inside that run's own box: the resolution
// adapts to the points, so tight clusters (even of spread 1e-12) are ordered as well as the rest.
void hilbertSort(const double* xyz, std::uint32_t* ids, std::size_t count)
{
  constexpr int kBits = 10;
  constexpr std::size_t kRunWorthRefining = 8;
  if (count < 2)
    return;
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
    lo[a] = hi[a] = xyz[3 * std::size_t(ids[0]) + a];
  for (std::size_t i = 1; i < count; ++i)
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], xyz[3 * std::size_t(ids[i]) + a]);
      hi[a] = std::max(hi[a], xyz[3 * std::size_t(ids[i]) + a]);
    }
  const double span = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (!(span > 0))
    return; // all points equal (duplicates): any order
  const double toGrid = ((1u << kBits) - 1) / span;
  std::vector<std::uint64_t> keys(count);
  std::vector<std::uint32_t> values(ids, ids + count);
  for (std::size_t i = 0; i < count; ++i)
  {
    const double* p = xyz + 3 * std::size_t(values[i]);
    std::uint32_t q[3];
    for (int a = 0; a < 3; ++a)
      q[a] = static_cast<std::uint32_t>((p[a] - lo[a]) * toGrid);
    keys[i] = hilbertIndex(q[0], q[1], q[2], kBits);
  }
  radixSort(keys, values, 3 * kBits);
  std::copy(values.begin(), values.end(), ids);
  for (std::size_t begin = 0; begin < count;)
  {
    std::size_t end = begin + 1;
    while (end < count && keys[end] == keys[begin])
      ++end;
    if (end - begin >= kRunWorthRefining && end - begin < count)
      hilbertSort(xyz, ids + begin, end - begin);
    begin = end;
  }
}

// Least-significant-digit radix sort of `values` by `keys` (stable), over the low `bits` bits.
// std::sort costs n log n comparisons; this is three linear passes for our 36-bit keys.
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

} // namespace fd3
