// A uniform grid of buckets over a box, for the covering's two lookups among many: the points
// whose images fall in a region, and the regions that may hold a sphere. Both were a scan of
// every point (or region) per region (or sphere), which rounds with many regions (slabs, a narrow
// shell) could not afford.
#ifndef fd3_Buckets_h
#define fd3_Buckets_h

#include "fd3/Bounds.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fd3
{

/// About `target` cells over `box`, as near cubes as its sides allow, one a side at least; items
/// are filed in the cells their box overlaps, clamped to the grid (an item beyond the box is in
/// its border cells). Ids are filed once, then read: no insertion after the first lookup.
class Buckets
{
public:
  Buckets(const Bounds& box, std::size_t target)
  {
    double volume = 1;
    int flat = 0;
    for (int k = 0; k < 3; ++k)
    {
      if (box.extent(k) > 0)
        volume *= box.extent(k);
      else
        ++flat;
    }
    const double side = flat == 3
      ? 1.0
      : std::pow(volume / double(std::max<std::size_t>(target, 1)), 1.0 / (3 - flat));
    for (int k = 0; k < 3; ++k)
    {
      lo_[k] = box.lo[k];
      const double cells = box.extent(k) > 0 ? std::ceil(box.extent(k) / side) : 1.0;
      n_[k] = int(std::clamp(cells, 1.0, 1024.0));
      inverse_[k] = box.extent(k) > 0 ? n_[k] / box.extent(k) : 0.0;
    }
    cells_.resize(std::size_t(n_[0]) * n_[1] * n_[2]);
    filed_.resize(cells_.size());
    rows_.resize(std::size_t(n_[1]) * n_[2]);
  }

  /// Files `id` in every cell that `region` overlaps.
  void file(std::uint32_t id, const Bounds& region)
  {
    int lo[3], hi[3];
    span(region, lo, hi);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
          cells_[index(i, j, k)].push_back(id);
  }

  /// Files `id` at point p, in its one cell, and keeps the bounds of the points filed in each
  /// cell and each row of cells along x, for visitCells() and visitCellsNear().
  void file(std::uint32_t id, const double p[3])
  {
    int at[3];
    for (int k = 0; k < 3; ++k)
      at[k] = cellOf(p[k], k);
    const std::size_t cell = index(at[0], at[1], at[2]);
    cells_[cell].push_back(id);
    filed_[cell].include(p);
    rows_[std::size_t(at[2]) * n_[1] + at[1]].include(p);
  }

  /// Calls visit(cell, filed, ids) for each cell that `region` overlaps: its index, below 2^30,
  /// the bounds of the points filed there (empty for none, or for items filed as regions), and
  /// the ids.
  template <typename Visit>
  void visitCells(const Bounds& region, Visit visit) const
  {
    int lo[3], hi[3];
    span(region, lo, hi);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          const std::size_t cell = index(i, j, k);
          visit(cell, filed_[cell], cells_[cell]);
        }
  }

  /// visitCells() of the cells that `region` overlaps and that may hold points within `radius` of
  /// `centre`, by the bounds of the points filed in their rows along x (filed as points only): a
  /// ball's cells, not its box's, where the ball dips into the points only as a cap.
  template <typename Visit>
  void visitCellsNear(
    const Bounds& region, const double centre[3], double radius, Visit visit) const
  {
    int lo[3], hi[3];
    span(region, lo, hi);
    // Wider than any rounding of a caller's distances.
    const double reach =
      radius + 1e-9 * (radius + std::fabs(centre[0]) + std::fabs(centre[1]) + std::fabs(centre[2]));
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
      {
        const Bounds& row = rows_[std::size_t(k) * n_[1] + j];
        double apart = 0; // squared, across the row
        for (int a = 1; a < 3; ++a)
        {
          const double gap = std::max({row.lo[a] - centre[a], centre[a] - row.hi[a], 0.0});
          apart += gap * gap;
        }
        if (row.empty() || !(apart <= reach * reach))
          continue;
        const double half = std::sqrt(reach * reach - apart);
        const int first = std::max(lo[0], cellOf(centre[0] - half, 0));
        const int last = std::min(hi[0], cellOf(centre[0] + half, 0));
        for (int i = first; i <= last; ++i)
        {
          const std::size_t cell = index(i, j, k);
          visit(cell, filed_[cell], cells_[cell]);
        }
      }
  }

  /// Calls visit(id) for each id filed in a cell that `region` overlaps (an id in several of
  /// them, as often).
  template <typename Visit>
  void visit(const Bounds& region, Visit visit) const
  {
    visitCells(region, [&](std::size_t, const Bounds&, const std::vector<std::uint32_t>& ids) {
      for (const std::uint32_t id : ids)
        visit(id);
    });
  }

private:
  int cellOf(double x, int k) const
  {
    const double c = std::floor((x - lo_[k]) * inverse_[k]);
    return c >= 0 ? int(std::min(c, double(n_[k] - 1))) : 0; // NaN too
  }
  void span(const Bounds& region, int lo[3], int hi[3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = cellOf(region.lo[k], k);
      hi[k] = std::max(lo[k], cellOf(region.hi[k], k));
    }
  }
  std::size_t index(int i, int j, int k) const
  {
    return (std::size_t(k) * std::size_t(n_[1]) + std::size_t(j)) * std::size_t(n_[0]) +
      std::size_t(i);
  }

  double lo_[3], inverse_[3];
  int n_[3];
  std::vector<std::vector<std::uint32_t>> cells_;
  std::vector<Bounds> filed_; // per cell, of the points filed there
  std::vector<Bounds> rows_;  // per row of cells along x, the same
};

} // namespace fd3

#endif
