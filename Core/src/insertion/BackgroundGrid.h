// The paper's background grid: regular cells over the bounding box of the points, each remembering
// the last vertex inserted in it. The walk for a new point starts from a vertex found by searching
// the cells layer by layer outwards from the point's own cell (the "onion"). Inserting threads
// read and write cells concurrently: a cell is a relaxed atomic, and what it holds is only a hint.
#ifndef fd3_BackgroundGrid_h
#define fd3_BackgroundGrid_h

#include "fd3/Bounds.h"
#include "system/Stretches.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>

namespace fd3
{

class BackgroundGrid
{
public:
  static constexpr std::uint32_t kEmpty = 0xFFFFFFFFu;

  /// Sizes the grid over `box` for about `pointsPerCell` of the `count` points per cell; 0
  /// disables it. The cells are emptied in the stretches of `fill`, where given.
  void build(
    std::size_t count, const Bounds& box, double pointsPerCell, const Stretches& fill = nullptr);
  bool enabled() const { return cellCount_ > 0; }

  /// A point's cell, found once for the search from it and the mark after its insertion.
  struct Cell
  {
    int ijk[3];
    std::size_t index;
  };
  Cell cellOf(const double* p) const
  {
    Cell c;
    cellCoordinates(p, c.ijk);
    c.index = index(c.ijk[0], c.ijk[1], c.ijk[2]);
    return c;
  }

  void markInserted(const Cell& c, std::uint32_t vertex)
  {
    cells_[c.index].store(vertex, std::memory_order_relaxed);
  }

  /// The vertex remembered by the first cell met when searching layer by layer outwards from
  /// cell c whose vertex passes `accept`, or kEmpty when the first `maxLayers` layers have none.
  template <typename Accept>
  std::uint32_t nearestInserted(const Cell& c, int maxLayers, Accept accept) const;
  std::uint32_t nearestInserted(const Cell& c, int maxLayers) const
  {
    return nearestInserted(c, maxLayers, [](std::uint32_t) { return true; });
  }

private:
  void cellCoordinates(const double* p, int ijk[3]) const;
  std::size_t index(int i, int j, int k) const
  {
    return (std::size_t(k) * dims_[1] + j) * dims_[0] + i;
  }
  template <typename Accept>
  std::uint32_t scanRow(int i0, int i1, int j, int k, Accept& accept) const;
  template <typename Accept>
  std::uint32_t scanLayer(const int c[3], int n, Accept& accept) const;
  std::uint32_t cell(std::size_t i) const { return cells_[i].load(std::memory_order_relaxed); }

  std::unique_ptr<std::atomic<std::uint32_t>[]> cells_;
  std::size_t cellCount_ = 0;
  static constexpr double kMaxCellsPerPoint = 8;
  double halfOrigin_[3] = {0, 0, 0};      // the box's lower corner, halved
  double inverseHalfSize_[3] = {0, 0, 0}; // cells per half unit
  int dims_[3] = {0, 0, 0};
};

template <typename Accept>
std::uint32_t BackgroundGrid::scanRow(int i0, int i1, int j, int k, Accept& accept) const
{
  if (j < 0 || j >= dims_[1] || k < 0 || k >= dims_[2])
    return kEmpty;
  i0 = std::max(i0, 0);
  i1 = std::min(i1, dims_[0] - 1);
  const std::size_t row = index(0, j, k);
  for (int i = i0; i <= i1; ++i)
    if (const std::uint32_t v = cell(row + i); v != kEmpty && accept(v))
      return v;
  return kEmpty;
}

// Layer n around cell c: the top and bottom squares (k = k0 +- n) and, between them, the open
// cylinder of the square rings at Chebyshev distance n (the paper's Fig. 10).
template <typename Accept>
std::uint32_t BackgroundGrid::scanLayer(const int c[3], int n, Accept& accept) const
{
  const int i0 = c[0] - n, i1 = c[0] + n;
  for (int k : {c[2] - n, c[2] + n})
    for (int j = c[1] - n; j <= c[1] + n; ++j)
      if (const std::uint32_t v = scanRow(i0, i1, j, k, accept); v != kEmpty)
        return v;
  for (int k = c[2] - n + 1; k <= c[2] + n - 1; ++k)
  {
    for (int j : {c[1] - n, c[1] + n})
      if (const std::uint32_t v = scanRow(i0, i1, j, k, accept); v != kEmpty)
        return v;
    for (int j = c[1] - n + 1; j <= c[1] + n - 1; ++j)
      for (int i : {i0, i1})
        if (const std::uint32_t v = scanRow(i, i, j, k, accept); v != kEmpty)
          return v;
  }
  return kEmpty;
}

template <typename Accept>
std::uint32_t BackgroundGrid::nearestInserted(const Cell& c, int maxLayers, Accept accept) const
{
  if (const std::uint32_t v = cell(c.index); v != kEmpty && accept(v))
    return v;
  const int widest = std::max({dims_[0], dims_[1], dims_[2]});
  for (int n = 1; n <= maxLayers && n < widest; ++n)
    if (const std::uint32_t v = scanLayer(c.ijk, n, accept); v != kEmpty)
      return v;
  return kEmpty;
}

} // namespace fd3

#endif
