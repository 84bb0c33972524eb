// Benchmark --scaling: a measured model of how Core's insertion scales with threads.
#ifndef fd3_benchmark_Scaling_h
#define fd3_benchmark_Scaling_h

#include <cstddef>
#include <string>
#include <vector>

namespace fd3bench
{

struct ScalingSettings
{
  std::vector<std::string> kinds;
  std::vector<std::size_t> sizes;
  std::vector<int> threads = {1, 2, 4, 8, 16, 32, 64};
  std::string csvFile, markdownFile;
};

/// Runs Core on every kind, size and thread count, and writes the model's table.
int scaling(const ScalingSettings& settings);

} // namespace fd3bench

#endif
