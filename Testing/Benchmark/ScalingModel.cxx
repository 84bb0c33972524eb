// The scaling model of Core's threads without VTK (Scaling.h has its command line): what
// `Benchmark --scaling` runs, in a program that links Core alone, so that it can be built
// statically and run on a many-core machine that has no ParaView.
#include "Scaling.h"

int main(int argc, char* argv[])
{
  return fd3bench::scalingMain(argc, argv);
}
