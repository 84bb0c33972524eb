// Voronoi cells of the same points by Core (fd3::voronoiCells, on each thread count asked for,
// with the cells' polyhedra and with their figures alone),
// by Voro++ where the benchmark is built with it (its container in the points' bounding box; each
// cell's volume, area and neighbours, and in a second run also its polyhedron, vertices and faces
// copied out as a program that draws or writes the cells does, as Core gives them), and by
// scipy.spatial.Voronoi (Qhull's unbounded diagram alone) where /usr/bin/python3 has scipy.
// Each run in a forked child with its own peak memory.
#include "VoronoiBench.h"

#include "Measure.h"
#include "PointSets.h"
#include "fd3/Voronoi.h"

#ifdef FD3_BENCHMARK_WITH_VOROPP
#include "VoroppRun.h"
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numeric>

namespace fd3bench
{
namespace
{
/// Core's cells; without `polyhedra`, their figures alone (volumes, areas, neighbours), as Voro++'s
/// first run gives them.
Measurement runCore(const fd3test::Points& p, int threads, bool polyhedra)
{
  fd3::VoronoiOptions options;
  options.threads = threads;
  options.polyhedra = polyhedra;
  const double caller0 = threadCpuSeconds();
  const auto t0 = Clock::now();
  const fd3::VoronoiCells cells = fd3::voronoiCells(p.data(), p.size() / 3, options);
  Measurement m;
  m.seconds = since(t0);
  const CoreModel model = coreModel(threadCpuSeconds() - caller0, cells.threadedWork);
  m.ran = cells.status == fd3::Status::Ok;
  m.figures = {std::accumulate(cells.volumes.begin(), cells.volumes.end(), 0.0),
    double(cells.numberOfCells()), model.seconds, model.serial};
  return m;
}

#ifdef FD3_BENCHMARK_WITH_VOROPP
/// Voro++'s cells (sweepCells()), with their polyhedra where asked.
Measurement runVoropp(const fd3test::Points& p, bool polyhedra)
{
  return runVoroppContainer(
    p, fd3::finiteBounds(p.data(), p.size() / 3), {false, false, false}, polyhedra);
}
#endif

/// scipy.spatial.Voronoi through /usr/bin/python3 on the points, written to a file first.
Measurement runScipy(const fd3test::Points& p, const std::string& script)
{
  const std::string file = "/tmp/fd3-voronoi-points.bin";
  if (FILE* out = std::fopen(file.c_str(), "wb"))
  {
    std::fwrite(p.data(), sizeof(double), p.size(), out);
    std::fclose(out);
  }
  Measurement m;
  FILE* in = popen(("/usr/bin/python3 " + script + " " + file + " 2>/dev/null").c_str(), "r");
  double regions = 0;
  if (in && std::fscanf(in, "%lf %lf %lf", &m.seconds, &m.peakMiB, &regions) == 3)
  {
    m.ran = true;
    m.figures = {0, regions};
  }
  else
    m.note = "scipy not available";
  if (in)
    pclose(in);
  std::remove(file.c_str());
  return m;
}
} // namespace

int voronoiMain(int argc, char* argv[], const VoronoiFilterRun& filter)
{
  RunSettings settings;
  settings.kinds = {"cube", "clusters", "molshell"};
  settings.sizes = {100000, 1000000};
  settings.threads = {1, 2};
  settings.limit = 600; // Voro++ on clustered points is slow
  if (!parseRunSettings(argc, argv, "--voronoi", settings))
    return 2;
  const std::string script = std::string(FD3_BENCHMARK_SOURCE_DIR) + "/scipy_voronoi.py";
  const auto wanted = [&](const char* method) {
    return settings.methods.empty() ||
      std::find(settings.methods.begin(), settings.methods.end(), method) != settings.methods.end();
  };
  std::ostringstream md, csv;
  md << "Machine: " << machineName() << ". Voronoi cells of the same points, one run per row, "
     << "each in a child process (peak: its memory above its input). Core and Voro++: cells in "
     << "the points' bounding box with volumes, areas and neighbours, and their polyhedra for "
     << "the Core rows but the figures ones and for Voro++ polyhedra (vertices and faces copied "
     << "out of each Voro++ cell); scipy: "
     << "scipy.spatial.Voronoi (Qhull's unbounded diagram, no clipping, volumes or areas). "
     << "Volume: the cells' total over the box's. Model (Core): the run on a core per thread, "
     << "from each thread's CPU time (Scaling.cxx), and its serial seconds; real only where each "
     << "thread has a core. filter: vtkFastVoronoi3D on a vtkPolyData of the points (its default "
     << "properties, NumberOfThreads the count after the dash), and the share of its time that "
     << "writing VTK's arrays takes (conversion).\n\n"
     << "| points | n | method | seconds | model s | serial s | conversion | peak MiB | B/point | "
        "volume / box | Voro++ / this | Voro++ polyhedra / this |\n"
     << "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  csv << "kind,n,method,seconds,model_seconds,serial_seconds,conversion_seconds,peak_mib,"
         "volume_fraction\n";
  for (const std::string& kind : settings.kinds)
    for (const std::size_t size : settings.sizes)
    {
      const fd3test::Points p = fd3test::generate(kind, size, 1);
      const std::size_t n = p.size() / 3;
      const double box = fd3::finiteBounds(p.data(), n).volume();
      std::vector<std::pair<std::string, Measurement>> rows;
      for (const bool polyhedra : {true, false})
        for (const int t : settings.threads)
        {
          const std::string suffix = std::to_string(t) + (polyhedra ? "" : " figures");
          if (wanted("Core"))
            rows.push_back(
              {"Core-" + suffix, measure([&] { return runCore(p, t, polyhedra); }, 1e9)});
          if (filter && wanted("filter"))
            rows.push_back(
              {"filter-" + suffix, measure([&] { return filter(p, t, polyhedra); }, 1e9)});
        }
#ifdef FD3_BENCHMARK_WITH_VOROPP
      if (wanted("Voro++"))
      {
        rows.push_back({"Voro++", measure([&] { return runVoropp(p, false); }, settings.limit)});
        rows.push_back(
          {"Voro++ polyhedra", measure([&] { return runVoropp(p, true); }, settings.limit)});
      }
#endif
      if (wanted("scipy"))
        rows.push_back({"scipy", runScipy(p, script)});
      double voropp = 0, voroppPolyhedra = 0;
      for (const auto& [name, m] : rows)
      {
        if (name == "Voro++" && m.ran)
          voropp = m.seconds;
        if (name == "Voro++ polyhedra" && m.ran)
          voroppPolyhedra = m.seconds;
      }
      auto ratio = [](double other, double seconds) {
        return other > 0 ? std::to_string(other / seconds).substr(0, 5) + "x" : std::string("-");
      };
      for (const auto& [name, m] : rows)
      {
        char line[256];
        if (!m.ran)
        {
          md << "| " << kind << " | " << n << " | " << name << " | " << m.note << " |\n";
          continue;
        }
        const double fraction = m.figures.empty() || m.figures[0] == 0 ? 0 : m.figures[0] / box;
        const bool modelled = m.figures.size() > 3;
        const std::string model = modelled ? std::to_string(m.figures[2]).substr(0, 6) : "-";
        const std::string serial = modelled ? std::to_string(m.figures[3]).substr(0, 5) : "-";
        char conversion[32] = "-";
        if (m.conversionSeconds > 0)
          std::snprintf(conversion, sizeof conversion, "%.3f s (%.0f%%)", m.conversionSeconds,
            100 * m.conversionSeconds / m.seconds);
        std::snprintf(line, sizeof line,
          "| %s | %zu | %s | %.3f | %s | %s | %s | %.0f | %.0f | %s | %s | %s |\n", kind.c_str(), n,
          name.c_str(), m.seconds, model.c_str(), serial.c_str(), conversion, m.peakMiB,
          m.peakMiB * 1048576.0 / double(n), fraction > 0 ? std::to_string(fraction).c_str() : "-",
          ratio(voropp, m.seconds).c_str(), ratio(voroppPolyhedra, m.seconds).c_str());
        md << line;
        csv << kind << ',' << n << ',' << name << ',' << m.seconds << ','
            << (modelled ? m.figures[2] : 0) << ',' << (modelled ? m.figures[3] : 0) << ','
            << m.conversionSeconds << ',' << m.peakMiB << ',' << fraction << '\n';
        std::cerr << kind << " " << n << " " << name << ": " << m.seconds << " s\n";
      }
    }
  writeReport(md, csv, settings.markdownFile, settings.csvFile);
  return 0;
}

} // namespace fd3bench
