// Insertion order: BRIO (Amenta, Choi, Rote 2003) with each round sorted along a Hilbert curve, so
// that consecutive points are close (short walks, warm caches) while rounds keep the randomness
// that bounds the expected work.
#ifndef fd3_InsertionOrder_h
#define fd3_InsertionOrder_h

#include "fd3/Delaunay.h"

#include <cstdint>
#include <vector>

namespace fd3
{

/// Position along a 3D Hilbert curve of a point whose coordinates are quantized to `bits` bits.
std::uint64_t hilbertIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits);

/// Stable sort of `values` by the low `bits` bits of `keys` (both are permuted).
void radixSort(std::vector<std::uint64_t>& keys, std::vector<std::uint32_t>& values, int bits);

/// Sorts ids along a Hilbert curve, refining the curve inside every crowded cell.
void hilbertSort(const double* xyz, std::uint32_t* ids, std::size_t count);

/// The order in which to insert the points `ids` (indices into xyz).
std::vector<std::uint32_t> insertionOrder(const double* xyz, std::vector<std::uint32_t> ids,
  InsertionOrder order, std::uint64_t seed);

} // namespace fd3

#endif
