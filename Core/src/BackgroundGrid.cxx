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

} // namespace fd3
