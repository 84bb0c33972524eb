// The paper's background grid: regular cells over the bounding box of the points, each remembering
// the last vertex inserted in it. The walk for a new point starts from a vertex found by searching
// the cells layer by layer outwards from the point's own cell (the "onion"). Inserting threads
// read and write cells concurrently: a cell is a relaxed atomic, and what it holds is only a hint.
#ifndef fd3_BackgroundGrid_h
#define fd3_BackgroundGrid_h

#include "Geometry.h"

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
  /// disables it.
  void build(std::size_t count, const Box& box, double pointsPerCell);
  bool enabled() const { return cellCount_ > 0; }

  void markInserted(const double* p, std::uint32_t vertex)
  {
    cells_[cellIndex(p)].store(vertex, std::memory_order_relaxed);
  }

  /// The vertex remembered by the first non-empty cell met when searching layer by layer outwards
  /// from p's cell, or kEmpty when the first `maxLayers` layers are all empty.
  std::uint32_t nearestInserted(const double* p, int maxLayers) const;

private:
  void cellCoordinates(const double* p, int ijk[3]) const;
  std::size_t cellIndex(const double* p) const
  {
    int ijk[3];
    cellCoordinates(p, ijk);
    return index(ijk[0], ijk[1], ijk[2]);
  }
  std::size_t index(int i, int j, int k) const
  {
    return (std::size_t(k) * dims_[1] + j) * dims_[0] + i;
  }
  std::uint32_t scanRow(int i0, int i1, int j, int k) const;
  std::uint32_t scanLayer(const int c[3], int n) const;
  std::uint32_t cell(std::size_t i) const { return cells_[i].load(std::memory_order_relaxed); }

  std::unique_ptr<std::atomic<std::uint32_t>[]> cells_;
  std::size_t cellCount_ = 0;
  double origin_[3] = {0, 0, 0};
  double inverseSize_[3] = {0, 0, 0};
  int dims_[3] = {0, 0, 0};
};

} // namespace fd3

#endif
