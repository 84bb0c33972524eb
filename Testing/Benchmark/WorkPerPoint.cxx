// One triangulation for Testing/Benchmark/work_per_point.py, which counts its instructions and
// cache misses under cachegrind: Core's fd3::triangulate on one thread (as the VTK filter runs it,
// without neighbours), or, where the benchmark is built with CGAL, its Delaunay_triangulation_3
// as Benchmark runs it (points with their ids, one range insertion, its spatial sort included).
//   WorkPerPoint <core|cgal> <kind> <points>
// prints: <tetrahedra>
#include "PointSets.h"
#include "fd3/Delaunay.h"

#ifdef FD3_BENCHMARK_WITH_CGAL
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#endif

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace
{
std::size_t runCore(const fd3test::Points& p)
{
  fd3::Options options;
  options.computeNeighbors = false;
  return fd3::triangulate(p.data(), p.size() / 3, options).numberOfTetrahedra();
}

#ifdef FD3_BENCHMARK_WITH_CGAL
std::size_t runCgal(const fd3test::Points& p)
{
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vertex = CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, Kernel>;
  using Cell = CGAL::Delaunay_triangulation_cell_base_3<Kernel>;
  using Data = CGAL::Triangulation_data_structure_3<Vertex, Cell, CGAL::Sequential_tag>;
  std::vector<std::pair<Kernel::Point_3, std::uint32_t>> points;
  points.reserve(p.size() / 3);
  for (std::size_t i = 0; i < p.size(); i += 3)
    points.emplace_back(Kernel::Point_3(p[i], p[i + 1], p[i + 2]), std::uint32_t(i / 3));
  const CGAL::Delaunay_triangulation_3<Kernel, Data> dt(points.begin(), points.end());
  return dt.number_of_finite_cells();
}
#endif
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 4)
  {
    std::fprintf(stderr, "usage: WorkPerPoint <core|cgal> <kind> <points>\n");
    return 2;
  }
  const std::string method = argv[1];
  const fd3test::Points p = fd3test::generate(argv[2], std::strtoull(argv[3], nullptr, 10), 1);
  std::size_t tetrahedra = 0;
  if (method == "core")
    tetrahedra = runCore(p);
#ifdef FD3_BENCHMARK_WITH_CGAL
  else if (method == "cgal")
    tetrahedra = runCgal(p);
#endif
  else
  {
    std::fprintf(stderr, "WorkPerPoint: no method %s in this build\n", method.c_str());
    return 2;
  }
  std::printf("%zu\n", tetrahedra);
  return 0;
}
