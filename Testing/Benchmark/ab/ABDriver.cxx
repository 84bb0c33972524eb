// One timed run of the kernel on a generated point set, for Testing/Benchmark/ab.sh, which builds
// this program against two versions of Core and runs them in turn. It uses only what every
// version since the public API settled offers: fd3::triangulate() and, where the version has
// them, fd3::voronoiCells() (FD3_AB_VORONOI) and the periodic unit box's fd3::triangulatePeriodic()
// and fd3::voronoiCellsPeriodic() (FD3_AB_PERIODIC; the points wrapped into it), and the regular
// tetrahedralization of weighted points (FD3_AB_WEIGHTED; radii uniform in [0.001, 0.01], as
// Benchmark --weighted draws them).
//   ABDriver <kind> <points> <threads> [voronoi | periodic | periodic-voronoi | weighted]
// prints: <seconds> <output hash> <tetrahedra or cells>, and the kernel's phase times to stderr.
// The seconds are the kernel's call alone, not the hashing of its output.
#include "PointSets.h"
#include "fd3/Delaunay.h"
#ifdef FD3_AB_VORONOI
#include "fd3/Voronoi.h"
#endif
#ifdef FD3_AB_PERIODIC
#include "fd3/Periodic.h"
#endif

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{
std::uint64_t mix(std::uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::uint64_t bitsOf(double x)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

/// A hash of the set of tetrahedra: each one's sorted vertex ids (every tetrahedron is positive,
/// so they name it), summed, so that the order of the tetrahedra does not count.
std::uint64_t hashOfTetrahedra(const fd3::Triangulation& t)
{
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < t.numberOfTetrahedra(); ++i)
  {
    std::uint32_t v[4];
    std::copy_n(t.tetrahedra.data() + 4 * i, 4, v);
    std::sort(v, v + 4);
    std::uint64_t h = 0;
    for (const std::uint32_t id : v)
      h = mix(h ^ id);
    sum += h;
  }
  return sum;
}

#ifdef FD3_AB_PERIODIC
/// A hash of the set of periodic tetrahedra: each one's vertices (id and offset, as placed: the
/// copy with its least vertex in the box) sorted, summed as hashOfTetrahedra() sums.
std::uint64_t hashOfPeriodic(const fd3::PeriodicTriangulation& t)
{
  std::uint64_t sum = 0;
  for (std::size_t i = 0; i < t.numberOfTetrahedra(); ++i)
  {
    std::uint64_t v[4];
    for (int j = 0; j < 4; ++j)
    {
      v[j] = std::uint64_t(t.tetrahedra[4 * i + j]) << 24;
      for (int k = 0; k < 3; ++k)
        v[j] |= std::uint64_t(std::uint8_t(t.offsets[12 * i + 3 * j + k])) << (16 - 8 * k);
    }
    std::sort(v, v + 4);
    std::uint64_t h = 0;
    for (const std::uint64_t id : v)
      h = mix(h ^ id);
    sum += h;
  }
  return sum;
}
#endif

#ifdef FD3_AB_VORONOI
/// A hash of the cells: each one's generator, volume and area bit for bit, and its faces'
/// neighbours in order, summed over the cells.
std::uint64_t hashOfCells(const fd3::VoronoiCells& cells)
{
  std::uint64_t sum = 0;
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
  {
    std::uint64_t h = mix(cells.generators[c]);
    h = mix(h ^ bitsOf(cells.volumes[c]));
    h = mix(h ^ bitsOf(cells.areas[c]));
    for (std::size_t f = cells.cellFaces[c]; f < cells.cellFaces[c + 1]; ++f)
      h = mix(h ^ cells.faceNeighbors[f]);
    sum += h;
  }
  return sum;
}
#endif
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 4)
  {
    std::fprintf(stderr,
      "usage: ABDriver <kind> <points> <threads> [voronoi | periodic | periodic-voronoi | "
      "weighted]\n");
    return 2;
  }
  const fd3test::Points p = fd3test::generate(argv[1], std::strtoull(argv[2], nullptr, 10), 1);
  const int threads = std::atoi(argv[3]);
  const std::string mode = argc > 4 ? argv[4] : "";
  const bool voronoi = mode == "voronoi";
#ifndef FD3_AB_WEIGHTED
  if (mode == "weighted")
  {
    std::fprintf(stderr, "ABDriver: this version of Core has no weighted points\n");
    return 2;
  }
#endif
  // Drawn before the clock starts, as the points are.
  const std::vector<double> weights = mode == "weighted"
    ? fd3test::randomWeights(p.size() / 3, 0.001, 0.01, 2)
    : std::vector<double>();
  const auto start = std::chrono::steady_clock::now();
  double seconds = 0;
  const auto stop = [&] {
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::uint64_t hash = 0;
  std::size_t count = 0;
  if (mode == "periodic" || mode == "periodic-voronoi")
  {
#ifdef FD3_AB_PERIODIC
    if (mode == "periodic")
    {
      fd3::Options options;
      options.threads = threads;
      const fd3::PeriodicTriangulation t =
        fd3::triangulatePeriodic(p.data(), p.size() / 3, fd3::PeriodicBox(), options);
      stop();
      hash = hashOfPeriodic(t);
      count = t.numberOfTetrahedra();
    }
    else
    {
      fd3::VoronoiOptions options;
      options.threads = threads;
      const fd3::VoronoiCells cells =
        fd3::voronoiCellsPeriodic(p.data(), p.size() / 3, fd3::PeriodicBox(), options);
      stop();
      hash = hashOfCells(cells);
      count = cells.numberOfCells();
    }
#else
    std::fprintf(stderr, "ABDriver: this version of Core has no periodic boxes\n");
    return 2;
#endif
  }
  else if (voronoi)
  {
#ifdef FD3_AB_VORONOI
    fd3::VoronoiOptions options;
    options.threads = threads;
    const fd3::VoronoiCells cells = fd3::voronoiCells(p.data(), p.size() / 3, options);
    stop();
    hash = hashOfCells(cells);
    count = cells.numberOfCells();
#else
    std::fprintf(stderr, "ABDriver: this version of Core has no Voronoi cells\n");
    return 2;
#endif
  }
  else
  {
    fd3::Options options;
    options.computeNeighbors = false; // as the VTK filter runs it
    options.threads = threads;
    const std::size_t n = p.size() / 3;
#ifdef FD3_AB_WEIGHTED
    const fd3::Triangulation t = mode == "weighted"
      ? fd3::triangulate(p.data(), weights.data(), n, options)
      : fd3::triangulate(p.data(), n, options);
#else
    const fd3::Triangulation t = fd3::triangulate(p.data(), n, options);
#endif
    stop();
    hash = hashOfTetrahedra(t);
    count = t.numberOfTetrahedra();
    const fd3::Statistics& s = t.stats;
    std::fprintf(stderr, "phases (s): sort %.3f locate %.3f cavity %.3f fill %.3f output %.3f\n",
      s.secondsSort, s.secondsLocate, s.secondsCavity, s.secondsFill, s.secondsOutput);
  }
  std::printf("%.4f %016" PRIx64 " %zu\n", seconds, hash, count);
  return 0;
}
