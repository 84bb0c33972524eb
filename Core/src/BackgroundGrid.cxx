#include "BackgroundGrid.h"

#include <algorithm>
#include <cmath>

namespace fd3
{

void BackgroundGrid::build(std::size_t count, const Box& box, double pointsPerCell)
{
  cells_.reset();
  cellCount_ = 0;
  if (pointsPerCell <= 0 || count == 0)
    return;
  // Cells as close to cubes as the box allows, about count / pointsPerCell of them; flat axes get one.
  const double cellsWanted = std::max(1.0, double(count) / pointsPerCell);
  double extent[3], volume = 1.0;
  int flatAxes = 0;
  for (int a = 0; a < 3; ++a)
  {
    extent[a] = box.extent(a);
    if (extent[a] > 0)
      volume *= extent[a];
    else
      ++flatAxes;
  }
  const double cellSize = std::pow(volume / cellsWanted, 1.0 / (3 - std::min(flatAxes, 2)));
  for (int a = 0; a < 3; ++a)
  {
    const double n = extent[a] > 0 && cellSize > 0 ? std::ceil(extent[a] / cellSize) : 1.0;
    dims_[a] = static_cast<int>(std::clamp(n, 1.0, 2048.0));
    origin_[a] = box.lo[a];
    inverseSize_[a] = extent[a] > 0 ? dims_[a] / extent[a] : 0.0;
  }
  cellCount_ = std::size_t(dims_[0]) * dims_[1] * dims_[2];
  cells_.reset(new std::atomic<std::uint32_t>[cellCount_]);
  for (std::size_t i = 0; i < cellCount_; ++i)
    cells_[i].store(kEmpty, std::memory_order_relaxed);
}

void BackgroundGrid::cellCoordinates(const double* p, int ijk[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    // Clamped as a double: points added after the build may lie far outside the grid's box.
    const double c = std::clamp((p[a] - origin_[a]) * inverseSize_[a], 0.0, double(dims_[a] - 1));
    ijk[a] = static_cast<int>(c);
  }
}

std::uint32_t BackgroundGrid::scanRow(int i0, int i1, int j, int k) const
{
  if (j < 0 || j >= dims_[1] || k < 0 || k >= dims_[2])
    return kEmpty;
  i0 = std::max(i0, 0);
  i1 = std::min(i1, dims_[0] - 1);
  const std::size_t row = index(0, j, k);
  for (int i = i0; i <= i1; ++i)
    if (const std::uint32_t v = cell(row + i); v != kEmpty)
      return v;
  return kEmpty;
}

// Layer n around cell c: the top and bottom squares (k = k0 +- n) and, between them, the open
// cylinder of the square rings at Chebyshev distance n (the paper's Fig. 10).
std::uint32_t BackgroundGrid::scanLayer(const int c[3], int n) const
{
  const int i0 = c[0] - n, i1 = c[0] + n;
  for (int k : {c[2] - n, c[2] + n})
    for (int j = c[1] - n; j <= c[1] + n; ++j)
      if (const std::uint32_t v = scanRow(i0, i1, j, k); v != kEmpty)
        return v;
  for (int k = c[2] - n + 1; k <= c[2] + n - 1; ++k)
  {
    for (int j : {c[1] - n, c[1] + n})
      if (const std::uint32_t v = scanRow(i0, i1, j, k); v != kEmpty)
        return v;
    for (int j = c[1] - n + 1; j <= c[1] + n - 1; ++j)
      for (int i : {i0, i1})
        if (const std::uint32_t v = scanRow(i, i, j, k); v != kEmpty)
          return v;
  }
  return kEmpty;
}

std::uint32_t BackgroundGrid::nearestInserted(const double* p, int maxLayers) const
{
  int c[3];
  cellCoordinates(p, c);
  if (const std::uint32_t v = cell(index(c[0], c[1], c[2])); v != kEmpty)
    return v;
  const int widest = std::max({dims_[0], dims_[1], dims_[2]});
  for (int n = 1; n <= maxLayers && n < widest; ++n)
    if (const std::uint32_t v = scanLayer(c, n); v != kEmpty)
      return v;
  return kEmpty;
}

} // namespace fd3
