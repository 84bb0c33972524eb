// Core's benchmarks that need no VTK: the scaling model of its threads (`--scaling`, as
// `Benchmark --scaling` runs it) and the Voronoi cells against Voro++ (`--voronoi`, as `Benchmark
// --voronoi`), in a program that links Core alone, so that it can be built statically and run on
// a many-core machine that has no ParaView.
#include "Scaling.h"
#include "VoronoiBench.h"

#include <string>

int main(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--voronoi")
      return fd3bench::voronoiMain(argc, argv);
  return fd3bench::scalingMain(argc, argv);
}
