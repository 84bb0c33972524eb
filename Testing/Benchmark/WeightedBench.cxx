// Weighted points, one thread, each run in a forked child with its own peak memory, the methods
// run in turn `repeat` times and each one's fastest kept:
//   Core    fd3::triangulate with weights: the regular tetrahedralization, without neighbours,
//           as the VTK filter runs it (and as the unweighted sets run)
//   CGAL    Regular_triangulation_3 (Epick), its own spatial sort, points made beforehand
//   cells   fd3::voronoiCells with weights, without polyhedra: each power cell's volume, area and
//           neighbours, in the points' bounding box
//   Voro++  container_poly over the same box: each radical cell's volume, area and neighbours
#include "WeightedBench.h"

#include "Measure.h"
#include "PointSets.h"
#include "fd3/Voronoi.h"

#ifdef FD3_BENCHMARK_WITH_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#endif
#ifdef FD3_BENCHMARK_WITH_VOROPP
#include "VoroppRun.h"
#endif

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace fd3bench
{
namespace
{
struct WeightedPoints
{
  fd3test::Points xyz;
  std::vector<double> radii, weights;
};

WeightedPoints uniformWithRadii(std::size_t n, double lo, double hi)
{
  return {fd3test::uniformCube(n, 1), fd3test::uniformRadii(n, lo, hi, 2),
    fd3test::randomWeights(n, lo, hi, 2)};
}

// figures: hidden points (Core and CGAL), or the volumes' sum and the cells with a volume.
Measurement runCore(const WeightedPoints& p)
{
  fd3::Options options;
  options.computeNeighbors = false;
  const auto t0 = Clock::now();
  const fd3::Triangulation t =
    fd3::triangulate(p.xyz.data(), p.weights.data(), p.radii.size(), options);
  Measurement m;
  m.seconds = since(t0);
  m.ran = t.status == fd3::Status::Ok;
  m.tetrahedra = double(t.numberOfTetrahedra());
  m.peakMiB = peakSoFarMiB();
  m.figures = {double(t.hidden.size())};
  return m;
}

Measurement runCells(const WeightedPoints& p)
{
  fd3::VoronoiOptions options;
  options.polyhedra = false;
  const auto t0 = Clock::now();
  const fd3::VoronoiCells cells =
    fd3::voronoiCells(p.xyz.data(), p.weights.data(), p.radii.size(), options);
  Measurement m;
  m.seconds = since(t0);
  m.ran = cells.status == fd3::Status::Ok;
  m.peakMiB = peakSoFarMiB();
  m.figures = {std::accumulate(cells.volumes.begin(), cells.volumes.end(), 0.0),
    double(
      std::count_if(cells.volumes.begin(), cells.volumes.end(), [](double v) { return v > 0; }))};
  return m;
}

#ifdef FD3_BENCHMARK_WITH_CGAL
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Regular = CGAL::Regular_triangulation_3<Kernel,
  CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t,
                                         Kernel, CGAL::Regular_triangulation_vertex_base_3<Kernel>>,
    CGAL::Regular_triangulation_cell_base_3<Kernel>>>;

Measurement runCgal(const WeightedPoints& p)
{
  const std::size_t n = p.radii.size();
  std::vector<std::pair<Regular::Weighted_point, std::uint32_t>> points;
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    points.emplace_back(
      Regular::Weighted_point(
        Kernel::Point_3(p.xyz[3 * i], p.xyz[3 * i + 1], p.xyz[3 * i + 2]), p.weights[i]),
      static_cast<std::uint32_t>(i));
  const auto t0 = Clock::now();
  const Regular regular(points.begin(), points.end());
  Measurement m;
  m.seconds = since(t0);
  m.ran = true;
  m.tetrahedra = double(regular.number_of_finite_cells());
  m.peakMiB = peakSoFarMiB();
  m.figures = {double(n - regular.number_of_vertices())};
  return m;
}
#endif

#ifdef FD3_BENCHMARK_WITH_VOROPP
Measurement runVoropp(const WeightedPoints& p)
{
  const fd3::Bounds b = fd3::finiteBounds(p.xyz.data(), p.radii.size());
  return runVoroppContainer(p.xyz, b, {false, false, false}, false, p.radii);
}
#endif

std::vector<ModeMethod<WeightedPoints>> methods(const std::vector<std::string>& wanted)
{
  std::vector<ModeMethod<WeightedPoints>> all = {
    {"Core", runCore}, {"CGAL", nullptr}, {"cells", runCells}, {"Voro++", nullptr}};
#ifdef FD3_BENCHMARK_WITH_CGAL
  all[1].run = runCgal;
#endif
#ifdef FD3_BENCHMARK_WITH_VOROPP
  all[3].run = runVoropp;
#endif
  return chooseMethods(std::move(all), wanted);
}

} // namespace

int weightedMain(int argc, char* argv[])
{
  RunSettings settings;
  settings.sizes = {100000, 1000000};
  settings.radii = {0.001, 0.01};
  if (!parseRunSettings(argc, argv, "--weighted", settings))
    return 2;
  const double lo = settings.radii[0], hi = settings.radii[1];
  const std::vector<ModeMethod<WeightedPoints>> chosen = methods(settings.methods);
  std::ostringstream md, csv;
  md << "Machine: " << machineName() << ". Uniform points in the unit cube, radii uniform in ["
     << lo << ", " << hi << "] (weight r^2); one thread; best of " << settings.repeat
     << " interleaved runs; peak memory each run's own. Core and CGAL: the regular "
        "tetrahedralization (hidden: points that are no vertex). cells and Voro++: each power "
        "cell's volume, area and neighbours in the points' box (cells with a volume).\n\n"
     << "| n | method | seconds | peak MiB | B/point | hidden or cells | vs CGAL | vs Voro++ |\n"
     << "|---:|---|---:|---:|---:|---:|---:|---:|\n";
  csv << "n,method,seconds,peak_mib,figure\n";
  for (const std::size_t n : settings.sizes)
  {
    const WeightedPoints p = uniformWithRadii(n, lo, hi);
    const std::vector<Measurement> best = bestOfInterleaved(chosen, p, n, settings);
    auto byName = [&](const char* name) { return measurementOf(chosen, best, name); };
    const Measurement cgal = byName("CGAL"), voropp = byName("Voro++");
    for (std::size_t i = 0; i < chosen.size(); ++i)
    {
      const Measurement& m = best[i];
      const double figure = m.figures.empty() ? -1 : m.figures.back();
      const bool cells = chosen[i].name == "cells" || chosen[i].name == "Voro++";
      md << "| " << n << " | " << chosen[i].name << " | " << cell(m, "%.3f", m.seconds) << " | "
         << cell(m, "%.0f", m.peakMiB) << " | " << cell(m, "%.0f", m.peakMiB * 1048576.0 / n)
         << " | " << cell(m, "%.0f", figure) << " | " << (cells ? "-" : speedup(m, cgal)) << " | "
         << (cells ? speedup(m, voropp) : "-") << " |\n";
      csv << n << ',' << chosen[i].name << ',' << (m.ran ? m.seconds : -1) << ',' << m.peakMiB
          << ',' << figure << '\n';
    }
  }
  writeReport(md, csv, settings.markdownFile, settings.csvFile);
  return 0;
}
} // namespace fd3bench
