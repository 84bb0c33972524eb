#include "PointSets.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

namespace fd3test
{

Points uniformCube(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Points p(3 * n);
  for (double& x : p)
    x = u(rng);
  return p;
}

Points uniformBall(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Points p;
  p.reserve(3 * n);
  while (p.size() < 3 * n)
  {
    const double x = u(rng), y = u(rng), z = u(rng);
    if (x * x + y * y + z * z <= 1)
      p.insert(p.end(), {x, y, z});
  }
  return p;
}

Points exactSphere(std::size_t n, std::uint64_t seed)
{
  // N odd with many divisors has 8 * sigma(N) representations as a sum of 4 squares.
  long N = 3 * 5 * 7 * 11;
  for (long prime : {13L, 17L, 19L, 23L})
    if (8.0 * N / 2 < 8.0 * n) // rough count of distinct points available
      N *= prime;
  std::set<std::array<long, 3>> found;
  const long r = static_cast<long>(std::sqrt(double(N)));
  for (long a = 0; a <= r; ++a)
    for (long b = -r; b <= r; ++b)
    {
      const long ab = a * a + b * b;
      if (ab > N)
        continue;
      for (long c = -r; c <= r; ++c)
      {
        const long rest = N - ab - c * c;
        if (rest < 0)
          continue;
        const long d = std::lround(std::sqrt(double(rest)));
        if (d * d != rest)
          continue;
        for (long dd : {d, -d})
          found.insert({a * a + b * b - c * c - dd * dd, 2 * (b * c + a * dd), 2 * (b * dd - a * c)});
      }
    }
  std::vector<std::array<long, 3>> all(found.begin(), found.end());
  std::mt19937_64 rng(seed);
  std::shuffle(all.begin(), all.end(), rng);
  if (all.size() > n)
    all.resize(n);
  Points p;
  p.reserve(3 * all.size());
  for (const auto& q : all)
    p.insert(p.end(), {double(q[0]), double(q[1]), double(q[2])});
  return p;
}

Points lattice(int k)
{
  Points p;
  p.reserve(3 * std::size_t(k) * k * k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l)
        p.insert(p.end(), {double(i), double(j), double(l)});
  return p;
}

Points clusters(std::size_t n, int clusterCount, double spread, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Points centres = uniformCube(static_cast<std::size_t>(clusterCount), seed + 1);
  Points p;
  p.reserve(3 * n);
  const std::size_t background = n / 10;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (i < background)
    {
      p.insert(p.end(), {u(rng), u(rng), u(rng)});
      continue;
    }
    const std::size_t c = i % static_cast<std::size_t>(clusterCount);
    for (int a = 0; a < 3; ++a)
      p.push_back(centres[3 * c + a] + spread * (u(rng) - 0.5));
  }
  return p;
}

Points thinSlab(std::size_t n, double thickness, std::uint64_t seed)
{
  Points p = uniformCube(n, seed);
  for (std::size_t i = 0; i < n; ++i)
    p[3 * i + 2] *= thickness;
  return p;
}

Points torusSurface(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 2 * M_PI);
  Points p;
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double s = u(rng), t = u(rng);
    p.insert(p.end(), {(1 + 0.4 * std::cos(t)) * std::cos(s), (1 + 0.4 * std::cos(t)) * std::sin(s), 0.4 * std::sin(t)});
  }
  return p;
}

Points generate(const std::string& kind, std::size_t n, std::uint64_t seed)
{
  if (kind == "cube")
    return uniformCube(n, seed);
  if (kind == "ball")
    return uniformBall(n, seed);
  if (kind == "sphere")
    return exactSphere(n, seed);
  if (kind == "lattice")
    return lattice(std::max(2, static_cast<int>(std::lround(std::cbrt(double(n))))));
  if (kind == "clusters")
    return clusters(n, 20, 1e-3, seed);
  if (kind == "slab")
    return thinSlab(n, 1e-3, seed);
  if (kind == "torus")
    return torusSurface(n, seed);
  throw std::invalid_argument("unknown point set: " + kind);
}

} // namespace fd3test
