// libFuzzer target: arbitrary bytes -> points -> fd3::triangulate -> the exact validator.
// Three decodings, chosen by the first byte, so that the fuzzer reaches both general and
// degenerate geometry: raw doubles (any bit pattern: NaN, Inf, subnormals and DBL_MAX included),
// small lattice coordinates (ties everywhere), and 16-bit integers scaled by a power of two
// (near-degenerate, exact in binary).
#include "ExactValidator.h"
#include "fd3/Delaunay.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <vector>

namespace
{
std::vector<double> decode(const std::uint8_t* data, std::size_t size)
{
  std::vector<double> xyz;
  if (size < 1)
    return xyz;
  const int mode = data[0] % 3;
  ++data;
  --size;
  if (mode == 0)
  {
    for (std::size_t i = 0; i + 8 <= size && xyz.size() < 3 * 200; i += 8)
    {
      std::uint64_t bits;
      std::memcpy(&bits, data + i, 8);
      double x;
      std::memcpy(&x, &bits, 8);
      xyz.push_back(x);
    }
  }
  else if (mode == 1)
  {
    for (std::size_t i = 0; i < size && xyz.size() < 3 * 300; ++i)
      xyz.push_back(data[i] % 6);
  }
  else
  {
    const int exponent = size ? static_cast<int>(data[0] % 64) - 32 : 0;
    for (std::size_t i = 1; i + 2 <= size && xyz.size() < 3 * 200; i += 2)
    {
      std::int16_t v;
      std::memcpy(&v, data + i, 2);
      xyz.push_back(std::ldexp(static_cast<double>(v), exponent));
    }
  }
  xyz.resize(xyz.size() / 3 * 3);
  return xyz;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::vector<double> xyz = decode(data, size);
  const std::size_t n = xyz.size() / 3;
  const fd3::Triangulation r = fd3::triangulate(xyz.data(), n);
  std::set<std::vector<double>> distinct;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(xyz[3 * i]) && std::isfinite(xyz[3 * i + 1]) && std::isfinite(xyz[3 * i + 2]))
      distinct.insert({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
  if (r.status == fd3::Status::Ok)
  {
    const fd3test::ValidityReport report = fd3test::checkTriangulation(xyz.data(), n, r.tetrahedra);
    if (!report.valid() || r.stats.insertedPoints != distinct.size())
    {
      std::fprintf(
        stderr, "invalid triangulation of %zu points: %s\n", n, report.summary().c_str());
      std::abort();
    }
  }
  else if (r.status == fd3::Status::TooFewPoints || r.status == fd3::Status::Empty)
  {
    if (distinct.size() >= 4)
      std::abort();
  }
  else if (r.status == fd3::Status::Degenerate)
  {
    // All distinct points must be coplanar: every point on the plane of 3 non-collinear ones.
    std::vector<std::vector<double>> q(distinct.begin(), distinct.end());
    for (std::size_t i = 2; i < q.size(); ++i)
    {
      const double* a = q[0].data();
      const double* b = q[1].data();
      const double* c = q[i].data();
      for (std::size_t j = 2; j < q.size(); ++j)
        if (fd3test::exactOrient3d(a, b, c, q[j].data()) != 0)
          std::abort();
    }
  }
  return 0;
}
