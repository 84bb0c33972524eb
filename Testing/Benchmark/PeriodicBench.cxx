// Points in the periodic unit box, one thread, each run in a forked child with its own peak
// memory, the methods run in turn `repeat` times and each one's fastest kept. The sets:
//   cube      uniform points
//   vacuum    uniform points in z < 0.3: a slab under a vacuum, as surface simulations have
//   planes    the point sets' planes z = 0, 0.1 and 0.37, a wide gap above the last
//   clusters  the point sets' 20 clusters, 1e-3 wide
// The methods:
//   Core    fd3::triangulatePeriodic: each periodic tetrahedron once, with its images
//   plain   fd3::triangulate of the same points, not periodic: what the periodic run adds
//   CGAL    Periodic_3_Delaunay_triangulation_3 (Epick), its own spatial sort, points made
//           beforehand
//   cells   fd3::voronoiCellsPeriodic without polyhedra: each cell's volume, area and neighbours
//   Voro++  its periodic container: each cell's volume, area and neighbours
// With radii (--radii lo,hi: uniform in [lo, hi], weight r^2), the weighted runs of each: the
// periodic regular tetrahedralization, CGAL's Periodic_3_regular_triangulation_3, power cells and
// Voro++'s periodic radical container (container_poly).
#include "PeriodicBench.h"

#include "Measure.h"
#include "PointSets.h"
#include "fd3/Periodic.h"

#ifdef FD3_BENCHMARK_WITH_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Periodic_3_Delaunay_triangulation_3.h>
#include <CGAL/Periodic_3_Delaunay_triangulation_traits_3.h>
#include <CGAL/Periodic_3_regular_triangulation_3.h>
#include <CGAL/Periodic_3_regular_triangulation_traits_3.h>
#endif
#ifdef FD3_BENCHMARK_WITH_VOROPP
#include "VoroppRun.h"
#endif

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

namespace fd3bench
{
namespace
{
/// The points, and where weighted their radii and weights (empty where not).
struct Particles
{
  fd3test::Points xyz;
  std::vector<double> radii, weights;
  std::size_t size() const { return xyz.size() / 3; }
  const double* weightsOrNull() const { return weights.empty() ? nullptr : weights.data(); }
};

// figures: the periodic tetrahedra (or tetrahedra), or the volumes' sum and the cells.
Measurement runCore(const Particles& p)
{
  const auto t0 = Clock::now();
  const fd3::PeriodicTriangulation t =
    fd3::triangulatePeriodic(p.xyz.data(), p.weightsOrNull(), p.size(), fd3::PeriodicBox());
  Measurement m;
  m.seconds = since(t0);
  m.ran = t.status == fd3::Status::Ok;
  m.tetrahedra = double(t.numberOfTetrahedra());
  m.peakMiB = peakSoFarMiB();
  m.figures = {double(t.imagePoints) / double(p.size())};
  return m;
}

Measurement runPlain(const Particles& p)
{
  const auto t0 = Clock::now();
  const fd3::Triangulation t = p.weights.empty()
    ? fd3::triangulate(p.xyz.data(), p.size(), fd3::Options())
    : fd3::triangulate(p.xyz.data(), p.weights.data(), p.size(), fd3::Options());
  Measurement m;
  m.seconds = since(t0);
  m.ran = t.status == fd3::Status::Ok;
  m.tetrahedra = double(t.numberOfTetrahedra());
  m.peakMiB = peakSoFarMiB();
  return m;
}

Measurement runCells(const Particles& p)
{
  fd3::VoronoiOptions options;
  options.polyhedra = false;
  const auto t0 = Clock::now();
  const fd3::VoronoiCells cells = fd3::voronoiCellsPeriodic(
    p.xyz.data(), p.weightsOrNull(), p.size(), fd3::PeriodicBox(), options);
  Measurement m;
  m.seconds = since(t0);
  m.ran = cells.status == fd3::Status::Ok;
  m.peakMiB = peakSoFarMiB();
  m.figures = {std::accumulate(cells.volumes.begin(), cells.volumes.end(), 0.0),
    double(cells.numberOfCells())};
  return m;
}

#ifdef FD3_BENCHMARK_WITH_CGAL
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using PeriodicCgal = CGAL::Periodic_3_Delaunay_triangulation_3<
  CGAL::Periodic_3_Delaunay_triangulation_traits_3<Kernel>>;

using RegularCgal =
  CGAL::Periodic_3_regular_triangulation_3<CGAL::Periodic_3_regular_triangulation_traits_3<Kernel>>;

Measurement runCgalRegular(const Particles& p)
{
  std::vector<RegularCgal::Weighted_point> points;
  points.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    points.emplace_back(
      RegularCgal::Bare_point(p.xyz[3 * i], p.xyz[3 * i + 1], p.xyz[3 * i + 2]), p.weights[i]);
  const auto t0 = Clock::now();
  RegularCgal regular(RegularCgal::Iso_cuboid(0, 0, 0, 1, 1, 1));
  regular.insert(points.begin(), points.end());
  Measurement m;
  m.seconds = since(t0);
  m.ran = true;
  m.tetrahedra = double(regular.number_of_cells());
  m.peakMiB = peakSoFarMiB();
  return m;
}

Measurement runCgal(const Particles& p)
{
  if (!p.weights.empty())
    return runCgalRegular(p);
  std::vector<PeriodicCgal::Point> points;
  points.reserve(p.size());
  for (std::size_t i = 0; i < p.xyz.size(); i += 3)
    points.emplace_back(p.xyz[i], p.xyz[i + 1], p.xyz[i + 2]);
  const auto t0 = Clock::now();
  PeriodicCgal periodic(points.begin(), points.end(), PeriodicCgal::Iso_cuboid(0, 0, 0, 1, 1, 1));
  Measurement m;
  m.seconds = since(t0);
  m.ran = true; // where one sheet is not enough, on 27: a valid result, counted per sheet
  m.tetrahedra = double(periodic.number_of_cells());
  m.peakMiB = peakSoFarMiB();
  return m;
}
#endif

#ifdef FD3_BENCHMARK_WITH_VOROPP
Measurement runVoropp(const Particles& p)
{
  fd3::Bounds unit;
  std::fill(unit.lo, unit.lo + 3, 0.0);
  std::fill(unit.hi, unit.hi + 3, 1.0);
  return runVoroppContainer(p.xyz, unit, {true, true, true}, false, p.radii);
}
#endif

/// The sets periodicSet() makes.
const std::vector<std::string> kPeriodicSets = {"cube", "vacuum", "planes", "clusters"};

/// The set `kind` of n points in the unit box, wrapped into it as every peer takes them; with
/// radii uniform in [lo, hi] where hi > 0.
Particles periodicSet(const std::string& kind, std::size_t n, double lo, double hi)
{
  Particles p{
    kind == "cube" || kind == "vacuum" ? fd3test::uniformCube(n, 1) : fd3test::generate(kind, n, 1),
    {}, {}};
  for (std::size_t i = 0; i < p.xyz.size(); ++i)
  {
    double& x = p.xyz[i];
    if (kind == "vacuum" && i % 3 == 2)
      x *= 0.3;
    x -= std::floor(x);
    if (x >= 1) // a tiny negative value's rounding
      x = 0;
  }
  if (hi > 0)
  {
    p.radii = fd3test::uniformRadii(p.size(), lo, hi, 2);
    p.weights = fd3test::randomWeights(p.size(), lo, hi, 2);
  }
  return p;
}

std::vector<ModeMethod<Particles>> methods(const std::vector<std::string>& wanted)
{
  std::vector<ModeMethod<Particles>> all = {{"Core", runCore}, {"plain", runPlain},
    {"CGAL", nullptr}, {"cells", runCells}, {"Voro++", nullptr}};
#ifdef FD3_BENCHMARK_WITH_CGAL
  all[2].run = runCgal;
#endif
#ifdef FD3_BENCHMARK_WITH_VOROPP
  all[4].run = runVoropp;
#endif
  return chooseMethods(std::move(all), wanted);
}

} // namespace

int periodicMain(int argc, char* argv[])
{
  RunSettings settings;
  settings.sizes = {100000, 1000000};
  settings.kinds = {"cube"};
  if (!parseRunSettings(argc, argv, "--periodic", settings))
    return 2;
  const double lo = settings.radii.empty() ? 0.0 : settings.radii[0];
  const double hi = settings.radii.empty() ? 0.0 : settings.radii[1];
  for (const std::string& kind : settings.kinds)
    if (std::find(kPeriodicSets.begin(), kPeriodicSets.end(), kind) == kPeriodicSets.end())
    {
      std::string known;
      for (const std::string& set : kPeriodicSets)
        known += (known.empty() ? "" : ", ") + set;
      std::fprintf(stderr, "Benchmark --periodic: no set %s (%s)\n", kind.c_str(), known.c_str());
      return 2;
    }
  const std::vector<ModeMethod<Particles>> chosen = methods(settings.methods);
  std::ostringstream md, csv;
  md << "Machine: " << machineName() << ". Points in the periodic unit box";
  if (hi > 0)
    md << ", radii uniform in [" << lo << ", " << hi << "] (weight r^2; the regular "
       << "tetrahedralization and power cells throughout)";
  md << "; one thread; best of " << settings.repeat
     << " interleaved runs; peak memory each run's own. Core "
        "and CGAL: the periodic Delaunay tetrahedralization (images: Core's shell, per point); "
        "plain: Core on the same points, not periodic. cells and Voro++: each periodic cell's "
        "volume, area and neighbours.\n\n"
     << "| set | n | method | seconds | peak MiB | tetrahedra or cells | images | vs CGAL | "
        "vs plain | vs Voro++ |\n"
     << "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|\n";
  csv << "set,n,method,seconds,peak_mib,count\n";
  for (const std::string& kind : settings.kinds)
    for (const std::size_t n : settings.sizes)
    {
      const Particles p = periodicSet(kind, n, lo, hi);
      const std::vector<Measurement> best = bestOfInterleaved(chosen, p, n, settings);
      auto byName = [&](const char* name) { return measurementOf(chosen, best, name); };
      const Measurement cgal = byName("CGAL"), plain = byName("plain"), voropp = byName("Voro++");
      for (std::size_t i = 0; i < chosen.size(); ++i)
      {
        const Measurement& m = best[i];
        const std::string& name = chosen[i].name;
        const bool cells = name == "cells" || name == "Voro++";
        const double count = cells ? (m.figures.size() > 1 ? m.figures[1] : -1) : m.tetrahedra;
        const std::string images =
          name == "Core" && !m.figures.empty() ? cell(m, "%.3f", m.figures[0]) : "-";
        // The plain run is the periodic one's baseline: its column says what periodic costs.
        const std::string vsPlain =
          name == "Core" && plain.ran && m.ran ? cell(m, "%.2fx", m.seconds / plain.seconds) : "-";
        md << "| " << kind << " | " << n << " | " << name << " | " << cell(m, "%.3f", m.seconds)
           << " | " << cell(m, "%.0f", m.peakMiB) << " | " << cell(m, "%.0f", count) << " | "
           << images << " | " << (name == "Core" ? speedup(m, cgal) : "-") << " | " << vsPlain
           << " | " << (name == "cells" ? speedup(m, voropp) : "-") << " |\n";
        csv << kind << ',' << n << ',' << name << ',' << (m.ran ? m.seconds : -1) << ','
            << m.peakMiB << ',' << count << '\n';
      }
    }
  writeReport(md, csv, settings.markdownFile, settings.csvFile);
  return 0;
}
} // namespace fd3bench
