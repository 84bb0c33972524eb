#include "insertion/BackgroundGrid.h"

#include <algorithm>
#include <cmath>

namespace fd3
{

void BackgroundGrid::build(
  std::size_t count, const Bounds& box, double pointsPerCell, const Stretches& fill)
{
  cells_.reset();
  cellCount_ = 0;
  if (!(pointsPerCell > 0) || count == 0)
    return;
  // Cells as close to cubes as the box allows, about count / pointsPerCell of them (at most
  // kMaxCellsPerPoint a point: more only cost memory); flat axes get one. In halves of the
  // coordinates, exact above the subnormals, so that boxes wider than DBL_MAX work too; the cell
  // size from logarithms where the volume is not a double.
  const double cellsWanted =
    std::clamp(double(count) / pointsPerCell, 1.0, kMaxCellsPerPoint * double(count));
  double halfExtent[3], halfVolume = 1.0, logVolume = 0;
  int flatAxes = 0;
  for (int a = 0; a < 3; ++a)
  {
    halfExtent[a] = box.hi[a] / 2 - box.lo[a] / 2;
    if (halfExtent[a] > 0)
    {
      halfVolume *= halfExtent[a];
      logVolume += std::log(halfExtent[a]);
    }
    else
      ++flatAxes;
  }
  const double dimensions = 3 - std::min(flatAxes, 2);
  double cellSize = std::pow(halfVolume / cellsWanted, 1.0 / dimensions);
  if (!(cellSize > 0 && std::isfinite(cellSize) && halfVolume < HUGE_VAL))
    cellSize = std::exp((logVolume - std::log(cellsWanted)) / dimensions);
  for (int a = 0; a < 3; ++a)
  {
    const double n = halfExtent[a] > 0 ? std::ceil(halfExtent[a] / cellSize) : 1.0;
    dims_[a] = static_cast<int>(n > 1 ? std::min(n, 2048.0) : 1.0);
    halfOrigin_[a] = box.lo[a] / 2;
    inverseHalfSize_[a] = halfExtent[a] > 0 ? dims_[a] / halfExtent[a] : 0.0;
  }
  cellCount_ = std::size_t(dims_[0]) * dims_[1] * dims_[2];
  cells_.reset(new std::atomic<std::uint32_t>[cellCount_]);
  forStretches(fill, cellCount_, [this](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      cells_[i].store(kEmpty, std::memory_order_relaxed);
  });
}

void BackgroundGrid::cellCoordinates(const double* p, int ijk[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    // Clamped as a double: points added after the build may lie far outside the grid's box, and a
    // subnormal box's scale may be infinite (0 times it is NaN, which goes to cell 0).
    const double c = (p[a] / 2 - halfOrigin_[a]) * inverseHalfSize_[a];
    ijk[a] = c > 0 ? static_cast<int>(std::min(c, double(dims_[a] - 1))) : 0;
  }
}

} // namespace fd3
