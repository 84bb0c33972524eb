// Voro++'s cell volumes, the reference of the Voronoi and power-cell tests: one sweep over any of
// its containers (plain or radical), which the tests fill themselves.
#ifndef fd3test_VoroppVolumes_h
#define fd3test_VoroppVolumes_h

#include <voro++/voro++.hh>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace fd3test
{
/// Blocks a side for n points in a cube-like box: about 5 points a block, Voro++'s advice.
inline int voroppBlocks(std::size_t n)
{
  return std::max(1, int(std::cbrt(double(n) / 5)));
}

/// The volume of each cell of `container`, by the id its point was put with (0 to n - 1); -1
/// where Voro++ makes no cell. Periodic containers take their own loop (c_loop_all_periodic).
template <typename Container, typename Loop = voro::c_loop_all>
std::vector<double> voroppVolumes(Container& container, std::size_t n)
{
  std::vector<double> volumes(n, -1);
  Loop loop(container);
  voro::voronoicell cell;
  if (loop.start())
    do
      if (container.compute_cell(cell, loop))
        volumes[std::size_t(loop.pid())] = cell.volume();
    while (loop.inc());
  return volumes;
}
} // namespace fd3test

#endif
