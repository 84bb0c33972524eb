// Insertion order: every point sorted once along an adaptive Hilbert curve, exact duplicates merged
// there (they end up side by side), then BRIO rounds (Amenta, Choi, Rote 2003) taken from that
// order, so that consecutive points are close (short walks, warm caches) while the rounds keep the
// randomness that bounds the expected work.
#ifndef fd3_InsertionOrder_h
#define fd3_InsertionOrder_h

#include "fd3/Bounds.h"
#include "fd3/Delaunay.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace fd3
{
class ThreadTeam;

/// Resolution of the curve: 2^kHilbertBits cells per axis (even: HilbertTable goes two levels at
/// a time).
constexpr int kHilbertBits = 10;

/// The position of cell (x, y, z) of the 2^kHilbertBits grid (each coordinate below
/// 2^kHilbertBits) along Skilling's Hilbert curve: consecutive positions are cells that share a
/// face, and every aligned block of 2^k cells a side takes 8^k consecutive positions.
std::uint32_t hilbertIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z);

/// Words holding a key in their high half and an id in their low half (in the kernel's
/// allocator: a sort's scratch is written right after it is made, never filled first).
using Words = std::vector<std::uint64_t, BulkAllocator<std::uint64_t>>;

/// Sorts `words` by the low `bits` bits of their keys, stably (least-significant-digit radix
/// sort: linear passes instead of std::sort's n log n comparisons); with a team, each thread
/// counts and scatters a stretch of the words.
void radixSortByHighHalf(Words& words, int bits, ThreadTeam* team);

struct InsertionPlan
{
  /// Input ids of the distinct points, in the order of insertion.
  IdArray order;
  /// (copy, original) input ids of the exact duplicates left out; the original is the copy with
  /// the smallest input id, whatever the order.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> duplicates;
  /// Where each BRIO round starts in `order` (one round for the other orders).
  std::vector<std::size_t> roundStarts;
};

/// Plans the insertion of the points `ids` (indices into xyz, all finite, within `box`); key[i] is
/// point i's perturbationKey() (Predicates.h). On every thread of `team`; the plan is the same
/// for any number of them.
InsertionPlan planInsertion(const double* xyz, const std::uint16_t* key, IdArray ids,
  const Bounds& box, InsertionOrder order, std::uint64_t seed, ThreadTeam& team);

/// Removes from the plan's order every point closer than `tolerance` to a point kept before it, and
/// returns (removed, kept) input id pairs: what inserting them one by one and skipping those within
/// the tolerance of an inserted point would do, decided before insertion so that it does not
/// depend on the threads' timing.
std::vector<std::pair<std::uint32_t, std::uint32_t>> skipClosePoints(
  const double* xyz, InsertionPlan& plan, double tolerance);

} // namespace fd3

#endif
