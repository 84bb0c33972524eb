// FastDelaunay3D benchmark: Core alone, vtkFastDelaunay3D through VTK, vtkDelaunay3D, and, when
// built with them, CGAL's Delaunay_triangulation_3 and TetGen, on deterministic point sets, in one
// run.
//
//   Benchmark [--kinds cube,ball,...] [--sizes 10000,100000] [--methods Core,CGAL,Core-2,...]
//             [--vtk-limit 60] [--validate-limit N] [--repeat K] [--markdown FILE] [--csv FILE]
//
// --repeat K runs the methods K times in turn on each point set and keeps each one's fastest run:
// on a shared machine whose speed drifts by tens of percent for minutes at a time, interleaved
// best-of-K ratios compare methods under the same conditions (the validator runs on the first).
//
// Methods: Core, vtkFastDelaunay3D, vtkDelaunay3D, CGAL, TetGen; "-T" after Core,
// vtkFastDelaunay3D or CGAL runs it on T threads (CGAL: its Parallel_tag triangulation with TBB).
//   Benchmark --table1 [--markdown FILE]     the paper's Table 1 for this kernel
//   Benchmark --scaling [--kinds ...] [--sizes N] [--threads 1,2,4,...] [--csv FILE]
//             [--markdown FILE]                the scaling model of Core's threads (Scaling.cxx)
//   Benchmark --voronoi [--kinds ...] [--sizes N] [--threads 1,2] [--methods Core,filter,...]
//             [--csv FILE] [--markdown FILE]
//                                            Voronoi cells: Core, Voro++, scipy (VoronoiBench.cxx)
//   Benchmark --weighted [--sizes N] [--radii LO,HI] [--repeat K]
//             [--methods Core,CGAL,cells,Voro++] [--csv FILE] [--markdown FILE]
//                                            weighted points: CGAL's regular triangulation,
//                                            Voro++'s radical cells (WeightedBench.cxx)
//   Benchmark --periodic [--kinds cube,vacuum,planes,clusters] [--sizes N] [--repeat K]
//             [--radii LO,HI] [--methods Core,plain,CGAL,cells,Voro++] [--csv FILE]
//             [--markdown FILE]              the periodic unit box: CGAL's periodic triangulation,
//                                            Voro++'s periodic container, weighted with radii
//                                            (PeriodicBench.cxx)
//
// Each measurement runs in a forked child, so its peak memory is its own (VmHWM after the
// child resets it) and a crash or a time-out costs one row, not the run.
#include "Measure.h"
#include "PeriodicBench.h"
#include "Scaling.h"
#include "VoronoiBench.h"
#include "VtkTestUtilities.h"
#include "WeightedBench.h"
#include "fd3/Delaunay.h"
#include "vtkFastDelaunay3D.h"
#include "vtkFastVoronoi3D.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDelaunay3D.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#ifdef FD3_BENCHMARK_WITH_CGAL
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif
#endif
#ifdef FD3_BENCHMARK_WITH_TETGEN
#include <tetgen.h>
#endif

#include <malloc.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

namespace
{
using namespace fd3bench;

/// The exact validator's verdict on a tetrahedralization, when the run is small enough.
template <typename Ids>
int validity(const fd3test::Points& p, const Ids& tets, std::size_t limit)
{
  if (p.size() / 3 > limit)
    return -1;
  return fd3test::checkTriangulation(p.data(), p.size() / 3, tets).valid() ? 1 : 0;
}

Measurement runCore(const fd3test::Points& p, std::size_t validateLimit, int threads)
{
  Measurement m;
  const auto t0 = Clock::now();
  fd3::Options options;
  options.computeNeighbors = false; // as the VTK filter runs it
  options.threads = threads;
  const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3, options);
  m.seconds = since(t0);
  m.tetrahedra = static_cast<double>(r.numberOfTetrahedra());
  m.walk = r.stats.meanWalk();
  m.maxWalk = static_cast<double>(r.stats.maxWalkSteps);
  m.peakMiB = peakSoFarMiB(); // before the validator's own memory
  m.valid = validity(p, r.tetrahedra, validateLimit);
  return m;
}

// Both VTK filters run with Tolerance 0 so that every method triangulates the same points.
template <typename Filter>
Measurement runVtkFilter(const fd3test::Points& p, std::size_t validateLimit, int threads)
{
  auto poly = fd3test::toPolyData(p);
  vtkNew<Filter> filter;
  filter->SetInputData(poly);
  filter->SetTolerance(0);
  filter->SetGlobalWarningDisplay(0);
  if constexpr (std::is_same_v<Filter, vtkFastDelaunay3D>)
    filter->SetNumberOfThreads(threads);
  Measurement m;
  const auto t0 = Clock::now();
  filter->Update();
  m.seconds = since(t0);
  if constexpr (std::is_same_v<Filter, vtkFastDelaunay3D>)
  {
    m.conversionSeconds = m.seconds - filter->GetKernelSeconds();
    m.walk = filter->GetMeanWalkLength();
    m.maxWalk = static_cast<double>(filter->GetMaxWalkLength());
  }
  m.tetrahedra = static_cast<double>(filter->GetOutput()->GetNumberOfCells());
  m.peakMiB = peakSoFarMiB();
  m.valid = validity(p, fd3test::tetrahedra(filter->GetOutput()), validateLimit);
  return m;
}

/// vtkFastVoronoi3D as a user runs it (default properties but the threads and, for the figures'
/// rows, GeneratePolyhedra), with the cells' total volume and count as Core's rows have them.
Measurement runVoronoiFilter(const fd3test::Points& p, int threads, bool polyhedra)
{
  auto poly = fd3test::toPolyData(p);
  vtkNew<vtkFastVoronoi3D> filter;
  filter->SetInputData(poly);
  filter->SetNumberOfThreads(threads);
  filter->SetGeneratePolyhedra(polyhedra);
  Measurement m;
  const auto t0 = Clock::now();
  filter->Update();
  m.seconds = since(t0);
  m.conversionSeconds = filter->GetConversionSeconds();
  vtkDataArray* volumes = filter->GetOutput()->GetCellData()->GetArray("Volume");
  double total = 0;
  for (vtkIdType c = 0; volumes && c < volumes->GetNumberOfTuples(); ++c)
    total += volumes->GetTuple1(c);
  m.figures = {total, double(filter->GetOutput()->GetNumberOfCells())};
  m.ran = filter->GetOutput()->GetNumberOfCells() > 0;
  m.peakMiB = peakSoFarMiB();
  return m;
}

#ifdef FD3_BENCHMARK_WITH_CGAL
/// The exact validator's verdict on a CGAL triangulation (CGAL's positive orientation is VTK's).
template <typename Triangulation>
int cgalValidity(const fd3test::Points& p, const Triangulation& dt, std::size_t limit)
{
  if (p.size() / 3 > limit)
    return -1;
  std::vector<std::uint32_t> tets;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
    tets.insert(tets.end(),
      {c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  return validity(p, tets, limit);
}

using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
#ifdef CGAL_LINKED_WITH_TBB
using CgalLocks = CGAL::Spatial_lock_grid_3<CGAL::Tag_priority_blocking>;
#else
using CgalLocks = CGAL::Default; // CGAL's locks need TBB, and so does its parallel build
#endif
template <typename Concurrency>
using CgalDelaunay = CGAL::Delaunay_triangulation_3<CgalKernel,
  CGAL::Triangulation_data_structure_3<
    CGAL::Triangulation_vertex_base_with_info_3<std::uint32_t, CgalKernel>,
    CGAL::Delaunay_triangulation_cell_base_3<CgalKernel>, Concurrency>,
  CGAL::Default,
  std::conditional_t<std::is_same_v<Concurrency, CGAL::Sequential_tag>, CGAL::Default, CgalLocks>>;

/// CGAL's Delaunay_triangulation_3, sequential or (threads > 1) its parallel version with TBB.
Measurement runCgal(const fd3test::Points& p, std::size_t validateLimit, int threads)
{
  std::vector<std::pair<CgalKernel::Point_3, std::uint32_t>> points;
  points.reserve(p.size() / 3);
  for (std::size_t i = 0; i < p.size(); i += 3)
    points.emplace_back(
      CgalKernel::Point_3(p[i], p[i + 1], p[i + 2]), static_cast<std::uint32_t>(i / 3));
  Measurement m;
  if (threads > 1)
  {
#ifdef CGAL_LINKED_WITH_TBB
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    const auto t0 = Clock::now();
    CGAL::Bbox_3 box;
    for (const auto& point : points)
      box += point.first.bbox();
    typename CgalDelaunay<CGAL::Parallel_tag>::Lock_data_structure locks(box, 50);
    CgalDelaunay<CGAL::Parallel_tag> dt(points.begin(), points.end(), &locks);
    m.seconds = since(t0);
    m.tetrahedra = static_cast<double>(dt.number_of_finite_cells());
    m.peakMiB = peakSoFarMiB();
    m.valid = cgalValidity(p, dt, validateLimit);
#else
    m.note = "no TBB";
#endif
    return m;
  }
  const auto t0 = Clock::now();
  CgalDelaunay<CGAL::Sequential_tag> dt(points.begin(), points.end()); // its own spatial sort
  m.seconds = since(t0);
  m.tetrahedra = static_cast<double>(dt.number_of_finite_cells());
  m.peakMiB = peakSoFarMiB();
  m.valid = cgalValidity(p, dt, validateLimit);
  return m;
}
#endif

#ifdef FD3_BENCHMARK_WITH_TETGEN
Measurement runTetgen(const fd3test::Points& p, std::size_t validateLimit)
{
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(p.size() / 3);
  in.pointlist = new REAL[p.size()];
  std::copy(p.begin(), p.end(), in.pointlist);
  Measurement m;
  const auto t0 = Clock::now();
  char switches[] = "Qz"; // Delaunay tetrahedralization of the points, quiet, ids from 0
  tetrahedralize(switches, &in, &out);
  m.seconds = since(t0);
  m.tetrahedra = out.numberoftetrahedra;
  m.peakMiB = peakSoFarMiB();
  if (p.size() / 3 <= validateLimit)
  {
    // TetGen drops exact duplicates and renumbers the points it keeps: its tetrahedra index
    // out.pointlist, not the input (terrain's 1% of copies made half of them look inverted).
    // Each kept point is mapped back to its input id, so the validator still checks the input.
    std::map<std::array<double, 3>, std::uint32_t> inputId;
    for (std::uint32_t i = 0; i < p.size() / 3; ++i)
      inputId.emplace(std::array<double, 3>{p[3 * i], p[3 * i + 1], p[3 * i + 2]}, i);
    std::vector<std::uint32_t> tets(
      out.tetrahedronlist, out.tetrahedronlist + 4 * out.numberoftetrahedra);
    for (std::uint32_t& id : tets)
    {
      const REAL* q = out.pointlist + 3 * std::size_t(id);
      const auto found = inputId.find({q[0], q[1], q[2]});
      id =
        found == inputId.end() ? std::uint32_t(p.size()) : found->second; // out of range: invalid
    }
    m.valid = validity(p, tets, validateLimit);
  }
  return m;
}
#endif

} // namespace

// The paper's Table 1 (HP 735, 1994): points, tetrahedra, tetrahedra per second, mean path.
struct PaperRow
{
  const char* name;
  std::size_t points;
  double tetrahedra, tetrahedraPerSecond, path;
};
constexpr PaperRow kPaperTable1[] = {{"Victor Hugo (surface)", 2034, 12750, 16139, 6},
  {"Peugeot (surface)", 4565, 27669, 15372, 7}, {"Engrenage (surface)", 3914, 24942, 15687, 12},
  {"Columbia (surface)", 6427, 43710, 15837, 7}, {"Ostab (surface)", 8505, 54698, 14893, 6},
  {"Random", 160008, 1077107, 14724, 6}};

/// Our kernel on inputs like the paper's: the surface models are not public, so surface samples of
/// a torus stand in for them, at the same sizes; the random case is the same, uniform points.
int table1(const std::string& markdownFile)
{
  std::ostringstream md;
  md << "Machine: " << machineName() << ". Best of 5 runs of Core, single thread.\n\n"
     << "| example | points | tetrahedra | tetrahedra/s | mean path | paper: tetrahedra | paper: "
        "tetrahedra/s (HP 735) | paper: path |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const PaperRow& row : kPaperTable1)
  {
    const bool random = std::string(row.name) == "Random";
    const fd3test::Points p =
      random ? fd3test::uniformCube(row.points, 3) : fd3test::torusSurface(row.points, row.points);
    double best = 1e30;
    fd3::Triangulation r;
    for (int run = 0; run < 5; ++run)
    {
      const auto t0 = Clock::now();
      r = fd3::triangulate(p.data(), p.size() / 3);
      best = std::min(best, since(t0));
    }
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %zu | %zu | %.3g | %.1f | %.0f | %.0f | %.0f |\n",
      random ? "Random" : (std::string(row.name) + " -> torus sample").c_str(), row.points,
      r.numberOfTetrahedra(), r.numberOfTetrahedra() / best, r.stats.meanWalk(), row.tetrahedra,
      row.tetrahedraPerSecond, row.path);
    md << line;
  }
  std::cout << md.str();
  if (!markdownFile.empty())
    std::ofstream(markdownFile) << md.str();
  return 0;
}

/// A method that the benchmark can time.
struct Method
{
  std::string name;
  std::function<Measurement(const fd3test::Points&, std::size_t)> run; // empty: not built
};

/// The method by name: "Core", "vtkFastDelaunay3D", "vtkDelaunay3D", "CGAL", "TetGen", and
/// "<name>-T" for T threads where the method has them.
Method method(const std::string& name)
{
  const std::size_t dash = name.rfind('-');
  const std::string base = dash == std::string::npos ? name : name.substr(0, dash);
  const int threads = dash == std::string::npos ? 1 : std::stoi(name.substr(dash + 1));
  using std::placeholders::_1;
  using std::placeholders::_2;
  Method m{name, {}};
  if (base == "Core")
    m.run = std::bind(runCore, _1, _2, threads);
  else if (base == "vtkFastDelaunay3D")
    m.run = std::bind(runVtkFilter<vtkFastDelaunay3D>, _1, _2, threads);
  else if (base == "vtkDelaunay3D" && threads == 1)
    m.run = std::bind(runVtkFilter<vtkDelaunay3D>, _1, _2, 1);
#ifdef FD3_BENCHMARK_WITH_CGAL
  else if (base == "CGAL")
    m.run = std::bind(runCgal, _1, _2, threads);
#endif
#ifdef FD3_BENCHMARK_WITH_TETGEN
  else if (base == "TetGen" && threads == 1)
    m.run = runTetgen;
#endif
  return m;
}

struct Settings
{
  std::vector<std::string> kinds = fd3test::pointSetNames();
  std::vector<std::size_t> sizes = {10000, 100000, 1000000};
  std::vector<Method> methods;
  double vtkLimit = 60;
  std::size_t validateLimit = 200000;
  int repeat = 1;
  std::string markdownFile, csvFile;
  bool paperTable = false;
};

/// The settings of the command line; false (with a message) on an unknown option.
bool parse(int argc, char* argv[], Settings& settings)
{
  for (const char* name : {"Core", "vtkFastDelaunay3D", "vtkDelaunay3D", "CGAL", "TetGen"})
    settings.methods.push_back(method(name));
  for (int i = 1; i < argc; i += 2)
  {
    const std::string key = argv[i], value = i + 1 < argc ? argv[i + 1] : "";
    if (key == "--table1")
    {
      settings.paperTable = true;
      --i;
    }
    else if (key == "--kinds")
      settings.kinds = split(value);
    else if (key == "--sizes")
    {
      settings.sizes.clear();
      for (const std::string& s : split(value))
        settings.sizes.push_back(static_cast<std::size_t>(std::stod(s)));
    }
    else if (key == "--methods")
    {
      settings.methods.clear();
      for (const std::string& name : split(value))
        settings.methods.push_back(method(name));
    }
    else if (key == "--vtk-limit")
      settings.vtkLimit = std::stod(value);
    else if (key == "--validate-limit")
      settings.validateLimit = static_cast<std::size_t>(std::stod(value));
    else if (key == "--repeat")
      settings.repeat = std::max(1, std::stoi(value));
    else if (key == "--markdown")
      settings.markdownFile = value;
    else if (key == "--csv")
      settings.csvFile = value;
    else
    {
      std::cerr << "unknown option " << key << "\n";
      return false;
    }
  }
  return true;
}

/// Every method on `p`, `repeat` times in turn, each one's fastest run kept (the validator runs
/// on the first). vtkDelaunay3D is skipped where the last size's time per point predicts more
/// than the limit.
std::vector<Measurement> measureAll(
  const Settings& settings, const fd3test::Points& p, double& vtkSecondsPerPoint)
{
  constexpr double kNoLimit = 1e9;
  const std::size_t n = p.size() / 3;
  std::vector<Measurement> rows(settings.methods.size());
  for (int r = 0; r < settings.repeat; ++r)
    for (std::size_t i = 0; i < settings.methods.size(); ++i)
    {
      const Method& method = settings.methods[i];
      const std::size_t validate = r == 0 ? settings.validateLimit : 0;
      Measurement m;
      if (!method.run)
        m.note = "not built";
      else if (method.name != "vtkDelaunay3D")
        m = measure([&] { return method.run(p, validate); }, kNoLimit);
      else if (vtkSecondsPerPoint * n * 1.5 > settings.vtkLimit) // grows faster than linearly
        m.note = "skipped (over " + std::to_string(int(settings.vtkLimit)) + " s)";
      else
      {
        m = measure([&] { return method.run(p, validate); }, settings.vtkLimit);
        vtkSecondsPerPoint = m.ran ? m.seconds / n : settings.vtkLimit; // a time-out stops larger
      }
      if (r == 0)
        rows[i] = m;
      else if (m.ran && (!rows[i].ran || m.seconds < rows[i].seconds))
      {
        m.valid = rows[i].valid;
        rows[i] = m;
      }
    }
  return rows;
}

/// The rows of one point set and size, as markdown, CSV and a progress line each.
void report(const std::string& kind, std::size_t n, const std::vector<Method>& methods,
  const std::vector<Measurement>& rows, std::ostream& md, std::ostream& csv)
{
  auto column = [&](const char* name) {
    const auto it =
      std::find_if(methods.begin(), methods.end(), [&](const Method& m) { return m.name == name; });
    return it == methods.end() ? -1 : static_cast<int>(it - methods.begin());
  };
  auto speedup = [&](const Measurement& m, int other) {
    if (other < 0)
      return std::string("-");
    const Measurement& o = rows[other];
    return (m.ran && o.ran) ? cell(m, "%.2fx", o.seconds / m.seconds) : std::string("-");
  };
  for (std::size_t i = 0; i < methods.size(); ++i)
  {
    const Measurement& m = rows[i];
    const bool walks = m.walk > 0;
    md << "| " << kind << " | " << n << " | " << methods[i].name << " | "
       << cell(m, "%.3f", m.seconds) << " | " << cell(m, "%.3g", n / m.seconds) << " | "
       << cell(m, "%.3g", m.tetrahedra / m.seconds) << " | " << cell(m, "%.0f", m.peakMiB) << " | "
       << cell(m, "%.0f", m.peakMiB * 1048576.0 / n) << " | "
       << (walks ? cell(m, "%.1f", m.walk) : "-") << " | "
       << (walks ? cell(m, "%.0f", m.maxWalk) : "-") << " | " << speedup(m, column("Core")) << " | "
       << speedup(m, column("vtkDelaunay3D")) << " | " << speedup(m, column("CGAL")) << " | "
       << (m.valid == 1 ? "valid" : (m.valid == 0 ? "INVALID" : "-")) << " |\n";
    csv << kind << ',' << n << ',' << methods[i].name << ',' << (m.ran ? m.seconds : -1) << ','
        << m.tetrahedra << ',' << m.peakMiB << ',' << m.valid << ',' << m.conversionSeconds << ','
        << m.walk << ',' << m.maxWalk << '\n';
    std::cerr << kind << " " << n << " " << methods[i].name << ": "
              << (m.ran ? std::to_string(m.seconds) + " s" : m.note)
              << (walks ? ", walk " + std::to_string(m.walk) + " max " + std::to_string(m.maxWalk)
                        : "")
              << "\n";
  }
}

int main(int argc, char* argv[])
{
  auto given = [&](const char* flag) {
    return std::find_if(argv + 1, argv + argc,
             [&](const char* a) { return std::string(a) == flag; }) != argv + argc;
  };
  if (given("--scaling"))
    return scalingMain(argc, argv);
  if (given("--voronoi"))
    return voronoiMain(argc, argv, runVoronoiFilter);
  if (given("--weighted"))
    return weightedMain(argc, argv);
  if (given("--periodic"))
    return periodicMain(argc, argv);
  Settings settings;
  if (!parse(argc, argv, settings))
    return 2;
  if (settings.paperTable)
    return table1(settings.markdownFile);

  std::ostringstream md, csv;
  md << "Machine: " << machineName() << ". "
     << (settings.repeat > 1
            ? "Best of " + std::to_string(settings.repeat) + " interleaved runs of every method. "
            : "")
     << "Kernel single-threaded; peak memory is each run's own "
     << "(above its input). Walk: tetrahedra visited per point location, mean and max. Speed-up "
     << "columns: the other method's time over this one's.\n\n"
     << "| points | n | method | seconds | points/s | tets/s | peak MiB | B/point | walk | max "
        "walk | vs Core | vs vtkDelaunay3D | vs CGAL | exact validity |\n"
     << "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  csv << "kind,n,method,seconds,tetrahedra,peak_mib,valid,conversion_seconds,walk,max_walk\n";
  for (const std::string& kind : settings.kinds)
  {
    double vtkSecondsPerPoint = 0; // from the last vtkDelaunay3D run, to predict the next
    for (std::size_t size : settings.sizes)
    {
      const fd3test::Points p = fd3test::generate(kind, size, 1);
      report(
        kind, p.size() / 3, settings.methods, measureAll(settings, p, vtkSecondsPerPoint), md, csv);
    }
  }
  writeReport(md, csv, settings.markdownFile, settings.csvFile);
  return 0;
}
