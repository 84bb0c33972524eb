// The benchmarks' measurement: each run in a forked child, so that its peak memory is its own
// (VmHWM after the child resets it) and a crash or a time-out costs one row, not the run.
#ifndef fd3_benchmark_Measure_h
#define fd3_benchmark_Measure_h

#include <malloc.h>
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fd3/Delaunay.h"

namespace fd3bench
{
using Clock = std::chrono::steady_clock;

struct Measurement
{
  bool ran = false;
  double seconds = 0;
  double tetrahedra = 0;
  double peakMiB = 0;
  double conversionSeconds = 0; // the filter's time outside the kernel (VTK arrays in and out)
  double walk = 0;
  double maxWalk = 0;
  int valid = -1;              // 1 valid, 0 invalid, -1 not checked
  std::vector<double> figures; // more, as a benchmark defines them
  std::string note;            // why it did not run; or, when it ran, a detail (one line)
};

/// The calling thread's CPU seconds.
inline double threadCpuSeconds()
{
  timespec now;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

/// A run on a core per thread, modelled from its threads' CPU times (Scaling.cxx): the calling
/// thread's CPU time outside the threaded work (`caller`: all of it), plus each stretch's longest
/// thread.
struct CoreModel
{
  double seconds = 0;
  double serial = 0;
};

inline CoreModel coreModel(double caller, const std::vector<fd3::ThreadedWork>& work)
{
  CoreModel model;
  model.serial = caller;
  for (const fd3::ThreadedWork& w : work)
  {
    model.serial -= w.callerSeconds;
    model.seconds += w.longest();
  }
  model.seconds += model.serial;
  return model;
}

inline double since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

inline long statusKiB(const char* field)
{
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field, 0) == 0)
      return std::stol(line.substr(std::strlen(field)));
  return 0;
}

inline long gBaseKiB = 0; // the child's resident memory before its work

inline double peakSoFarMiB()
{
  return (statusKiB("VmHWM:") - gBaseKiB) / 1024.0;
}

/// The measurement as one line: the fixed fields, the figures' count and figures, then the note.
inline std::string serialize(const Measurement& m)
{
  std::ostringstream line;
  line.precision(9);
  line << m.seconds << ' ' << m.tetrahedra << ' ' << m.peakMiB << ' ' << m.valid << ' '
       << m.conversionSeconds << ' ' << m.walk << ' ' << m.maxWalk << ' ' << m.figures.size();
  for (const double f : m.figures)
    line << ' ' << f;
  line << ' ' << m.note;
  return line.str();
}

inline Measurement deserialize(const std::string& text)
{
  Measurement m;
  std::istringstream line(text);
  std::size_t figures = 0;
  line >> m.seconds >> m.tetrahedra >> m.peakMiB >> m.valid >> m.conversionSeconds >> m.walk >>
    m.maxWalk >> figures;
  m.figures.resize(line ? figures : 0);
  for (double& f : m.figures)
    line >> f;
  m.ran = static_cast<bool>(line);
  line.get();
  std::getline(line, m.note);
  return m;
}

/// Runs `work` in a child process; the child reports its Measurement, with its peak memory above
/// what it inherited. Gives up after `limit` seconds.
template <typename Work>
Measurement measure(Work work, double limit)
{
  int fds[2];
  if (pipe(fds) != 0)
    return {};
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(fds[0]);
    malloc_trim(0); // pages the parent freed must not be reused unseen by the RSS counters
    std::ofstream("/proc/self/clear_refs") << "5"; // reset VmHWM to the current RSS
    gBaseKiB = statusKiB("VmRSS:");
    Measurement m = work();
    if (m.peakMiB == 0)
      m.peakMiB = peakSoFarMiB();
    const std::string line = serialize(m);
    if (write(fds[1], line.data(), line.size()) < 0)
      _exit(2);
    _exit(0);
  }
  close(fds[1]);
  Measurement m;
  const auto start = Clock::now();
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0)
  {
    if (since(start) > limit)
    {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      close(fds[0]);
      m.note = "timed out";
      return m;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::string line;
  char buffer[4096];
  for (ssize_t got; (got = read(fds[0], buffer, sizeof buffer)) > 0;)
    line.append(buffer, static_cast<std::size_t>(got));
  close(fds[0]);
  if (line.empty() || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
  {
    m.note = "failed";
    return m;
  }
  return deserialize(line);
}

/// Prints the markdown table and writes it and the CSV to their files, where named.
inline void writeReport(const std::ostringstream& md, const std::ostringstream& csv,
  const std::string& markdownFile, const std::string& csvFile)
{
  std::fwrite(md.str().data(), 1, md.str().size(), stdout);
  if (!markdownFile.empty())
    std::ofstream(markdownFile) << md.str();
  if (!csvFile.empty())
    std::ofstream(csvFile) << csv.str();
}

inline std::vector<std::string> split(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    out.push_back(item);
  return out;
}

/// A table cell: `value` in `format` where the run ran, else why not.
inline std::string cell(const Measurement& m, const char* format, double value)
{
  if (!m.ran)
    return m.note.empty() ? "skipped" : m.note;
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

/// The options that `--scaling`, `--voronoi`, `--weighted` and `--periodic` share; defaults are
/// each mode's.
struct RunSettings
{
  std::vector<std::string> kinds;
  std::vector<std::size_t> sizes;
  std::vector<int> threads;
  std::vector<std::string> methods; ///< the ones to run; empty for all
  double limit = 1e9;               ///< seconds for one run
  int repeat = 1;                   ///< interleaved runs of every method, where a mode takes it
  std::vector<double> radii;        ///< lo, hi: points with radii uniform in [lo, hi]; empty: none
  std::string csvFile, markdownFile;
};

/// Reads [--kinds K,..] [--sizes N,..] [--threads T,..] [--methods M,..] [--limit S] [--repeat K]
/// [--radii LO,HI] [--csv F] [--markdown F] into `settings`, skipping the mode's own `flag`; false
/// (with a message) on any other option.
inline bool parseRunSettings(int argc, char* argv[], const char* flag, RunSettings& settings)
{
  for (int i = 1; i < argc; i += 2)
  {
    const std::string key = argv[i], value = i + 1 < argc ? argv[i + 1] : "";
    if (key == flag)
      --i;
    else if (key == "--kinds")
      settings.kinds = split(value);
    else if (key == "--methods")
      settings.methods = split(value);
    else if (key == "--sizes" || key == "--threads")
    {
      std::vector<std::size_t> numbers;
      for (const std::string& s : split(value))
        numbers.push_back(static_cast<std::size_t>(std::stod(s)));
      if (key == "--sizes")
        settings.sizes = numbers;
      else
        settings.threads.assign(numbers.begin(), numbers.end());
    }
    else if (key == "--limit")
      settings.limit = std::stod(value);
    else if (key == "--radii")
    {
      settings.radii.clear();
      for (const std::string& s : split(value))
        settings.radii.push_back(std::stod(s));
      settings.radii.resize(2, settings.radii.empty() ? 0.0 : settings.radii[0]);
    }
    else if (key == "--repeat")
      settings.repeat = std::max(1, std::stoi(value));
    else if (key == "--csv")
      settings.csvFile = value;
    else if (key == "--markdown")
      settings.markdownFile = value;
    else
    {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return false;
    }
  }
  return true;
}

/// A method of a benchmark mode: its name and its run on the mode's input; `run` is empty where
/// the benchmark was built without it.
template <typename Input>
struct ModeMethod
{
  std::string name;
  std::function<Measurement(const Input&)> run;
};

/// The methods of `all` that `wanted` names, in the order of `all`; all of them where it names
/// none.
template <typename Input>
std::vector<ModeMethod<Input>> chooseMethods(
  std::vector<ModeMethod<Input>> all, const std::vector<std::string>& wanted)
{
  if (wanted.empty())
    return all;
  std::vector<ModeMethod<Input>> chosen;
  for (const ModeMethod<Input>& m : all)
    if (std::find(wanted.begin(), wanted.end(), m.name) != wanted.end())
      chosen.push_back(m);
  return chosen;
}

/// Each method's fastest of settings.repeat rounds on `input` in which every method runs once in
/// turn (interleaved), each run measured in a forked child; "not built" where a method has no
/// run. Every run's time goes to stderr after `size`.
template <typename Input>
std::vector<Measurement> bestOfInterleaved(const std::vector<ModeMethod<Input>>& methods,
  const Input& input, std::size_t size, const RunSettings& settings)
{
  std::vector<Measurement> best(methods.size());
  for (int r = 0; r < settings.repeat; ++r)
    for (std::size_t i = 0; i < methods.size(); ++i)
    {
      if (!methods[i].run)
      {
        best[i].note = "not built";
        continue;
      }
      const Measurement m = measure([&] { return methods[i].run(input); }, settings.limit);
      if (m.ran && (!best[i].ran || m.seconds < best[i].seconds))
        best[i] = m;
      std::cerr << size << " " << methods[i].name << ": " << (m.ran ? m.seconds : -1.0) << " s\n";
    }
  return best;
}

/// The measurement in `best` of the method called `name`, or an empty one where none is.
template <typename Input>
Measurement measurementOf(const std::vector<ModeMethod<Input>>& methods,
  const std::vector<Measurement>& best, const std::string& name)
{
  for (std::size_t i = 0; i < methods.size(); ++i)
    if (methods[i].name == name)
      return best[i];
  return Measurement();
}

/// How many times faster m ran than other, or "-" where either did not run.
inline std::string speedup(const Measurement& m, const Measurement& other)
{
  return m.ran && other.ran ? cell(m, "%.2fx", other.seconds / m.seconds) : std::string("-");
}

/// CPU model, hardware threads and memory.
inline std::string machineName()
{
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.rfind("model name", 0) == 0)
    {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  std::ostringstream out;
  out << cpu << ", " << std::thread::hardware_concurrency() << " threads, "
      << (sysconf(_SC_PHYS_PAGES) * sysconf(_SC_PAGE_SIZE) >> 30) << " GiB";
  return out.str();
}

} // namespace fd3bench

#endif
