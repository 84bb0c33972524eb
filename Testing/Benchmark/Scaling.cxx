// A measured model of Core's scaling with threads, for machines with more cores than this one.
//
// With a core per thread, a run would take the calling thread's serial work (its CPU time outside
// the threaded work) plus, for each stretch of threaded work (fd3::ThreadedWork), the CPU time of
// its longest thread:
//   M(T) = serial + sum over stretches of max over threads of thread CPU time,
//   S(T) = M(1) / M(T),   serial fraction = serial / M(T).
// Each thread's time is read from its own CPU clock, so the model holds when the threads share
// fewer cores (oversubscribed). What it leaves out is what cores cost each other on a real
// machine (memory bandwidth, caches, the mesh's cache lines moving between cores): only a run
// there shows that. As a check of the bookkeeping, the threads' CPU times and the serial time
// add up to the process's CPU time (getrusage), which every row reports.
#include "Scaling.h"

#include "Measure.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"

#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <numeric>

namespace fd3bench
{
namespace
{
double processCpuSeconds()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// The figures of a row, in Measurement::figures.
enum Figure
{
  kModelSeconds,
  kSerialSeconds,
  kLeftFraction,
  kThreadCpuSeconds,
  kProcessCpuSeconds,
  kFigures
};

/// The share of each kind of insertion pass's points that it put off, summed over the rounds, and
/// the CPU time of every kind of threaded work, all threads': "pass 1 29.5% 0.81 s, ...".
std::string passesLeft(const std::vector<fd3::ThreadedWork>& work)
{
  struct Sum
  {
    double points = 0, left = 0, seconds = 0;
  };
  std::map<std::string, Sum> phases;
  for (const fd3::ThreadedWork& w : work)
  {
    Sum& sum = phases[w.phase];
    sum.points += double(w.points);
    sum.left += double(w.left);
    sum.seconds += std::accumulate(w.threadSeconds.begin(), w.threadSeconds.end(), 0.0);
  }
  std::string text;
  for (const auto& [name, sum] : phases)
  {
    const bool pass = name.rfind("insertion ", 0) == 0;
    char item[96];
    std::snprintf(item, sizeof item, "%s%s", text.empty() ? "" : ", ",
      (pass ? name.substr(std::string("insertion ").size()) : name).c_str());
    text += item;
    if (pass)
    {
      std::snprintf(item, sizeof item, " %.1f%%", 100.0 * sum.left / sum.points);
      text += item;
    }
    std::snprintf(item, sizeof item, " %.2f s", sum.seconds);
    text += item;
  }
  return text.empty() ? "serial" : text;
}

Measurement runModel(const fd3test::Points& p, int threads)
{
  fd3::Options options;
  options.computeNeighbors = false; // as the VTK filter runs it
  options.threads = threads;
  const double caller0 = threadCpuSeconds(), process0 = processCpuSeconds();
  const auto t0 = Clock::now();
  const fd3::Triangulation r = fd3::triangulate(p.data(), p.size() / 3, options);
  Measurement m;
  m.seconds = since(t0);
  const double caller = threadCpuSeconds() - caller0, process = processCpuSeconds() - process0;
  m.tetrahedra = static_cast<double>(r.numberOfTetrahedra());
  double helpers = 0, inParallel = 0;
  for (const fd3::ThreadedWork& w : r.threadedWork)
  {
    helpers +=
      std::accumulate(w.threadSeconds.begin(), w.threadSeconds.end(), 0.0) - w.callerSeconds;
    inParallel += double(w.points - w.left);
  }
  const CoreModel model = coreModel(caller, r.threadedWork);
  m.figures.resize(kFigures);
  m.figures[kModelSeconds] = model.seconds;
  m.figures[kSerialSeconds] = model.serial;
  m.figures[kLeftFraction] = 1.0 - inParallel / double(r.stats.insertedPoints);
  m.figures[kThreadCpuSeconds] = caller + helpers;
  m.figures[kProcessCpuSeconds] = process;
  char phases[96];
  std::snprintf(phases, sizeof phases, "; sort %.3f s, output %.3f s", r.stats.secondsSort,
    r.stats.secondsOutput);
  m.note = passesLeft(r.threadedWork) + phases;
  return m;
}

void header(std::ostream& md, std::ostream& csv)
{
  md << "Machine: " << machineName() << ". Core, one run per row, threads oversubscribed where "
     << "they outnumber the cores. Speed-up: the one-thread run's seconds over this run's (real "
        "only where "
     << "each thread has a core). Model: serial CPU time plus, for every stretch of threaded "
     << "work, its longest thread's CPU time (Testing/Benchmark/Scaling.cxx). Left: the points "
     << "no parallel pass inserted (small rounds, passes left out, points put off by the last "
     << "pass), inserted serially. Thread and process CPU: the threads' CPU times and the serial "
     << "time summed, and getrusage's figure, which they must match.\n\n"
     << "| points | n | threads | seconds | speed-up | model s | model speed-up | serial | left | "
        "put off per pass; serial phases | thread CPU s | process CPU s | peak MiB | B/point |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n";
  csv << "kind,n,threads,seconds,model_seconds,model_speedup,serial_fraction,left_fraction,"
         "thread_cpu_seconds,process_cpu_seconds,peak_mib\n";
}

void row(const std::string& kind, std::size_t n, int threads, const Measurement& m,
  const Measurement& one, std::ostream& md, std::ostream& csv)
{
  if (!m.ran || m.figures.size() != std::size_t(kFigures))
  {
    md << "| " << kind << " | " << n << " | " << threads << " | " << m.note << " |\n";
    std::cerr << kind << " " << n << " T=" << threads << ": " << m.note << "\n";
    return;
  }
  const double model = m.figures[kModelSeconds];
  const double oneThreadModel = one.ran ? one.figures[kModelSeconds] : 0;
  const double speedup = oneThreadModel > 0 ? oneThreadModel / model : 0;
  const double wallSpeedup = one.ran ? one.seconds / m.seconds : 0;
  const double serialFraction = m.figures[kSerialSeconds] / model;
  char line[512];
  std::snprintf(line, sizeof line,
    "| %s | %zu | %d | %.3f | %.2f | %.3f | %.2f | %.2f%% | %.2f%% | %s | %.3f | %.3f | %.0f | "
    "%.0f "
    "|\n",
    kind.c_str(), n, threads, m.seconds, wallSpeedup, model, speedup, 100 * serialFraction,
    100 * m.figures[kLeftFraction], m.note.c_str(), m.figures[kThreadCpuSeconds],
    m.figures[kProcessCpuSeconds], m.peakMiB, m.peakMiB * 1048576.0 / double(n));
  md << line;
  std::snprintf(line, sizeof line, "%s,%zu,%d,%.6f,%.6f,%.4f,%.6f,%.6f,%.6f,%.6f,%.1f\n",
    kind.c_str(), n, threads, m.seconds, model, speedup, serialFraction, m.figures[kLeftFraction],
    m.figures[kThreadCpuSeconds], m.figures[kProcessCpuSeconds], m.peakMiB);
  csv << line;
  std::cerr << kind << " " << n << " T=" << threads << ": " << m.seconds << " s (" << wallSpeedup
            << "x), model " << model << " s, speed-up " << speedup << ", serial "
            << 100 * serialFraction << "%, " << m.note << "\n";
}

int scaling(const RunSettings& settings)
{
  std::vector<int> threads = settings.threads;
  if (std::find(threads.begin(), threads.end(), 1) == threads.end())
    threads.insert(threads.begin(), 1); // the model's speed-up is over one thread's model
  std::ostringstream md, csv;
  header(md, csv);
  for (const std::string& kind : settings.kinds)
    for (const std::size_t size : settings.sizes)
    {
      const fd3test::Points p = fd3test::generate(kind, size, 1);
      const std::size_t n = p.size() / 3;
      const Measurement one = measure([&] { return runModel(p, 1); }, settings.limit);
      for (const int t : threads)
        row(kind, n, t, t == 1 ? one : measure([&] { return runModel(p, t); }, settings.limit), one,
          md, csv);
    }
  writeReport(md, csv, settings.markdownFile, settings.csvFile);
  return 0;
}
} // namespace

int scalingMain(int argc, char* argv[])
{
  RunSettings settings;
  settings.kinds = fd3test::pointSetNames();
  settings.sizes = {1000000};
  settings.threads = {1, 2, 4, 8, 16, 32, 64};
  return parseRunSettings(argc, argv, "--scaling", settings) ? scaling(settings) : 2;
}

} // namespace fd3bench
