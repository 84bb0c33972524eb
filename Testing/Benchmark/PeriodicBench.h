// Benchmark --periodic: points in the periodic unit box (uniform; a slab under a vacuum, planes,
// clusters), one thread. Core's periodic tetrahedralization against CGAL's
// Periodic_3_Delaunay_triangulation_3 and against Core on the same points unperiodic (the
// periodic run's extra cost), and Core's periodic Voronoi cells against Voro++'s periodic
// container, like for like (PeriodicBench.cxx).
#ifndef fd3_benchmark_PeriodicBench_h
#define fd3_benchmark_PeriodicBench_h

namespace fd3bench
{
/// The command line of the periodic benchmark, as `Benchmark --periodic` takes it:
///   [--kinds cube,vacuum,planes,clusters] [--sizes N1,N2] [--repeat K] [--radii LO,HI]
///   [--methods Core,plain,CGAL,cells,Voro++] [--csv FILE] [--markdown FILE]
/// 2 on an unknown option.
int periodicMain(int argc, char* argv[]);
} // namespace fd3bench

#endif
