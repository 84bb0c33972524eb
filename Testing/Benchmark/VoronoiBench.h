// Benchmark --voronoi: Core's Voronoi cells against Voro++ and scipy.spatial.Voronoi.
#ifndef fd3_benchmark_VoronoiBench_h
#define fd3_benchmark_VoronoiBench_h

namespace fd3bench
{
/// The command line of the Voronoi benchmark, as `Benchmark --voronoi` takes it:
///   [--kinds K1,K2] [--sizes N1,N2] [--threads 1,2,...] [--limit SECONDS] [--csv FILE]
///   [--markdown FILE]
/// ("--voronoi" itself is skipped; --limit bounds each Voro++ run); 2 on an unknown option.
int voronoiMain(int argc, char* argv[]);
} // namespace fd3bench

#endif
