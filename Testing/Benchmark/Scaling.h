// Benchmark --scaling: a measured model of how Core's insertion scales with threads.
#ifndef fd3_benchmark_Scaling_h
#define fd3_benchmark_Scaling_h

namespace fd3bench
{

/// The command line of the scaling model, as `Benchmark --scaling` and `ScalingModel` take it:
///   [--kinds K1,K2] [--sizes N1,N2] [--threads 1,2,4,...] [--limit SECONDS] [--csv FILE]
///   [--markdown FILE]
/// ("--scaling" itself is skipped). Runs Core on every kind, size and thread count, and writes
/// the model's table; 2 on an unknown option.
int scalingMain(int argc, char* argv[]);

} // namespace fd3bench

#endif
