// Benchmark --weighted: weighted points, one thread. Core's regular tetrahedralization against
// CGAL's Regular_triangulation_3, and Core's power cells against Voro++'s radical cells
// (container_poly), like for like: each cell's volume, area and neighbours (WeightedBench.cxx).
#ifndef fd3_benchmark_WeightedBench_h
#define fd3_benchmark_WeightedBench_h

namespace fd3bench
{
/// The command line of the weighted benchmark, as `Benchmark --weighted` takes it:
///   [--sizes N1,N2] [--radii LO,HI] [--repeat K] [--methods Core,CGAL,cells,Voro++]
///   [--csv FILE] [--markdown FILE]
/// on uniform points in the unit cube with radii uniform in [LO, HI] (0.001, 0.01 by default);
/// 2 on an unknown option.
int weightedMain(int argc, char* argv[]);
} // namespace fd3bench

#endif
