// Benchmark --voronoi: Core's Voronoi cells against Voro++ and scipy.spatial.Voronoi, and, where
// the program has VTK, the Fast Voronoi 3D filter beside them.
#ifndef fd3_benchmark_VoronoiBench_h
#define fd3_benchmark_VoronoiBench_h

#include "Measure.h"
#include "PointSets.h"

#include <functional>

namespace fd3bench
{
/// One run of the VTK filter on the points: its seconds, and its conversion's (the writing of
/// VTK's arrays) in conversionSeconds.
using VoronoiFilterRun =
  std::function<Measurement(const fd3test::Points& points, int threads, bool polyhedra)>;

/// The command line of the Voronoi benchmark, as `Benchmark --voronoi` takes it:
///   [--kinds K1,K2] [--sizes N1,N2] [--threads 1,2,...] [--methods Core,filter,Voro++,scipy]
///   [--limit SECONDS] [--csv FILE] [--markdown FILE]
/// ("--voronoi" itself is skipped; --limit bounds each Voro++ run); 2 on an unknown option.
/// With `filter`, its runs join Core's, on each thread count, with and without polyhedra.
int voronoiMain(int argc, char* argv[], const VoronoiFilterRun& filter = nullptr);
} // namespace fd3bench

#endif
