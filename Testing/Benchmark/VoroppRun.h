// Voro++'s side of the Voronoi and power-cell benchmarks: the blocks of its container, one sweep
// over the cells of any container (plain or radical) that computes what Core's cells give, and
// the timed run of a plain container, periodic or not.
#ifndef fd3_benchmark_VoroppRun_h
#define fd3_benchmark_VoroppRun_h

#include "Measure.h"
#include "fd3/Bounds.h"

#include <voro++/voro++.hh>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace fd3bench
{
/// Blocks for n points in box b: about 5 points a block, Voro++'s advice, as cubic as the box
/// allows.
inline std::array<int, 3> voroppBlocks(const fd3::Bounds& b, std::size_t n)
{
  const double side = std::cbrt(5 * b.volume() / double(n));
  std::array<int, 3> blocks{};
  for (int a = 0; a < 3; ++a)
    blocks[a] = std::max(1, int(b.extent(a) / side));
  return blocks;
}

/// What one sweep found: the cells' total volume and area, the cells made, and those of them
/// with a volume (a radical container's hidden points have none).
struct VoroppSweep
{
  double volume = 0, area = 0;
  std::size_t cells = 0, withVolume = 0;
};

/// Every cell of `container` with its volume, area and neighbours; with `polyhedra`, also its
/// vertices (in the box's coordinates) and faces, appended to arrays of all the cells as a VTK
/// polyhedron's face stream (each face's size, then its vertices).
template <typename Container>
VoroppSweep sweepCells(Container& container, bool polyhedra)
{
  voro::c_loop_all loop(container);
  voro::voronoicell_neighbor cell;
  std::vector<int> neighbors, faces;
  std::vector<double> vertices, points;
  std::vector<long long> faceStream;
  VoroppSweep sweep;
  if (loop.start())
    do
      if (container.compute_cell(cell, loop))
      {
        const double volume = cell.volume();
        sweep.volume += volume;
        sweep.area += cell.surface_area();
        cell.neighbors(neighbors);
        ++sweep.cells;
        sweep.withVolume += volume > 0;
        if (!polyhedra)
          continue;
        double x, y, z;
        loop.pos(x, y, z);
        cell.vertices(x, y, z, vertices);
        cell.face_vertices(faces);
        const auto first = static_cast<long long>(points.size() / 3);
        points.insert(points.end(), vertices.begin(), vertices.end());
        for (std::size_t k = 0; k < faces.size(); k += std::size_t(faces[k]) + 1)
        {
          faceStream.push_back(faces[k]);
          for (int i = 1; i <= faces[k]; ++i)
            faceStream.push_back(first + faces[k + i]);
        }
      }
    while (loop.inc());
  return sweep;
}

/// Voro++'s cells of the points of p (x, y, z each) in box b, periodic along the axes where
/// `periodic` is set: a container (voroppBlocks()) made and filled, then sweepCells(), timed from
/// the container's making; with `radii` (one per point), the radical container's. Figures: the
/// volumes' sum, the cells made and those with a volume.
inline Measurement runVoroppContainer(const std::vector<double>& p, const fd3::Bounds& b,
  const std::array<bool, 3>& periodic, bool polyhedra, const std::vector<double>& radii = {})
{
  const std::size_t n = p.size() / 3;
  const std::array<int, 3> blocks = voroppBlocks(b, n);
  auto fillAndSweep = [&](auto& box, auto put) {
    for (std::size_t i = 0; i < n; ++i)
      put(box, i);
    return sweepCells(box, polyhedra);
  };
  const auto t0 = Clock::now();
  VoroppSweep sweep;
  if (radii.empty())
  {
    voro::container box(b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2], b.hi[2], blocks[0], blocks[1],
      blocks[2], periodic[0], periodic[1], periodic[2], 8);
    sweep = fillAndSweep(box, [&](voro::container& c, std::size_t i) {
      c.put(int(i), p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    });
  }
  else
  {
    voro::container_poly box(b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2], b.hi[2], blocks[0],
      blocks[1], blocks[2], periodic[0], periodic[1], periodic[2], 8);
    sweep = fillAndSweep(box, [&](voro::container_poly& c, std::size_t i) {
      c.put(int(i), p[3 * i], p[3 * i + 1], p[3 * i + 2], radii[i]);
    });
  }
  Measurement m;
  m.seconds = since(t0);
  m.ran = true;
  m.figures = {sweep.volume, double(sweep.cells), double(sweep.withVolume)};
  return m;
}
} // namespace fd3bench

#endif
