#include "PointSets.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
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

std::vector<double> uniformRadii(std::size_t n, double lo, double hi, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> radius(lo, hi);
  std::vector<double> r(n);
  for (double& x : r)
    x = radius(rng);
  return r;
}

std::vector<double> randomWeights(std::size_t n, double lo, double hi, std::uint64_t seed)
{
  std::vector<double> w = uniformRadii(n, lo, hi, seed);
  for (double& x : w)
    x *= x;
  return w;
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
  // N odd with many divisors has 8 * sigma(N) representations as a sum of 4 squares. Their
  // enumeration costs N^1.5: the largest N here gives about 1M distinct points in a minute.
  long N = 3 * 5 * 7 * 11;
  for (long prime : {13L, 17L, 19L})
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
          found.insert(
            {a * a + b * b - c * c - dd * dd, 2 * (b * c + a * dd), 2 * (b * dd - a * c)});
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
    p.insert(p.end(),
      {(1 + 0.4 * std::cos(t)) * std::cos(s), (1 + 0.4 * std::cos(t)) * std::sin(s),
        0.4 * std::sin(t)});
  }
  return p;
}

Points cylinderSurface(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), height(0, 1);
  Points p;
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double t = angle(rng);
    p.insert(p.end(), {0.5 * std::cos(t), 0.5 * std::sin(t), height(rng)});
  }
  return p;
}

namespace
{
/// A direction uniform on the unit sphere.
std::array<double, 3> randomDirection(std::mt19937_64& rng)
{
  std::normal_distribution<double> normal;
  for (;;)
  {
    const double x = normal(rng), y = normal(rng), z = normal(rng);
    const double r = std::sqrt(x * x + y * y + z * z);
    if (r > 1e-6)
      return {x / r, y / r, z / r};
  }
}
} // namespace

Points noisySphereShell(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
  Points p;
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto d = randomDirection(rng);
    const double r = 1 + noise(rng);
    p.insert(p.end(), {r * d[0], r * d[1], r * d[2]});
  }
  return p;
}

Points overlappingScans(std::size_t n, std::uint64_t seed)
{
  constexpr int kScans = 5;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> offset(-1e-4, 1e-4), angleOf(0.5e-4, 1.5e-4);
  Points p;
  p.reserve(3 * n);
  for (int scan = 0; scan < kScans; ++scan)
  {
    // A small rotation (angle ~1e-4 about a random axis, Rodrigues' formula) and translation.
    const auto axis = randomDirection(rng);
    const double angle = angleOf(rng), c = std::cos(angle), s = std::sin(angle);
    const double shift[3] = {offset(rng), offset(rng), offset(rng)};
    const std::size_t count = n / kScans + (scan < static_cast<int>(n % kScans) ? 1 : 0);
    for (std::size_t i = 0; i < count; ++i)
    {
      const auto d = randomDirection(rng);
      const double bump =
        1 + 0.15 * std::sin(5 * d[0]) * std::cos(4 * d[1]) * std::sin(3 * d[2] + 1);
      const double q[3] = {bump * d[0], bump * d[1], bump * d[2]};
      const double along = axis[0] * q[0] + axis[1] * q[1] + axis[2] * q[2];
      const double cross[3] = {axis[1] * q[2] - axis[2] * q[1], axis[2] * q[0] - axis[0] * q[2],
        axis[0] * q[1] - axis[1] * q[0]};
      for (int a = 0; a < 3; ++a)
        p.push_back(q[a] * c + cross[a] * s + axis[a] * along * (1 - c) + shift[a]);
    }
  }
  return p;
}

Points lidarTerrain(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  const double side = std::sqrt(0.25 * double(n)); // metres, for 4 points per square metre
  std::uniform_real_distribution<double> u(0, side);
  const double x0 = 512345.0, y0 = 498765.0;
  auto snap = [](double x) { return std::round(x * 100) / 100; }; // 1 cm
  Points p;
  p.reserve(3 * n);
  const std::size_t repeated = n / 100;
  while (p.size() < 3 * (n - repeated))
  {
    const double x = u(rng), y = u(rng);
    const double z = 100 + 8 * std::sin(x / 37.0) * std::cos(y / 53.0) +
      3 * std::sin((x + 2 * y) / 11.0) + 0.5 * std::cos(x / 3.1 - y / 4.3);
    p.insert(p.end(), {snap(x0 + x), snap(y0 + y), snap(z)});
  }
  std::uniform_int_distribution<std::size_t> pick(0, n - repeated - 1);
  for (std::size_t i = 0; i < repeated; ++i)
  {
    const std::size_t k = pick(rng);
    p.insert(p.end(), {p[3 * k], p[3 * k + 1], p[3 * k + 2]});
  }
  return p;
}

Points molecule(std::size_t atoms, std::uint64_t seed, std::vector<double>& radii)
{
  constexpr double kBond = 1.5, kClosest = 2.5;
  // C, N, O, S, H and how many in a hundred atoms of a protein's heavy atoms and polar hydrogens.
  constexpr double kRadius[5] = {1.70, 1.55, 1.52, 1.80, 1.20};
  constexpr int kShare[5] = {50, 14, 15, 1, 20};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_int_distribution<int> percent(0, 99);
  const double ball = std::cbrt(3 * double(atoms) / (4 * M_PI * 0.01));
  Points p = {0, 0, 0};
  radii.assign(1, kRadius[0]);
  while (radii.size() < atoms)
  {
    const std::size_t last = radii.size() - 1;
    double q[3];
    for (int attempt = 0;; ++attempt)
    {
      double d[3] = {gauss(rng), gauss(rng), gauss(rng)};
      const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int k = 0; k < 3; ++k)
        q[k] = p[3 * last + k] + kBond * d[k] / length;
      if (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] > ball * ball && attempt < 100)
        continue;
      bool clear = true;
      for (std::size_t i = 0; i + 1 < last && clear; ++i)
        clear = (q[0] - p[3 * i]) * (q[0] - p[3 * i]) +
            (q[1] - p[3 * i + 1]) * (q[1] - p[3 * i + 1]) +
            (q[2] - p[3 * i + 2]) * (q[2] - p[3 * i + 2]) >=
          kClosest * kClosest;
      if (clear || attempt >= 100)
        break;
    }
    p.insert(p.end(), q, q + 3);
    int element = 0, pick = percent(rng);
    while (pick >= kShare[element])
      pick -= kShare[element++];
    radii.push_back(kRadius[element]);
  }
  return p;
}

Points molecularShell(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  constexpr double kThickness = 4;
  // Lattice sites in the shell: about 4 pi R^2 * thickness, with 5% to spare for the subsample.
  const double inner = std::sqrt(1.05 * double(n) / (4 * M_PI * kThickness));
  const double outer = inner + kThickness;
  const long reach = static_cast<long>(std::ceil(outer));
  std::vector<std::array<long, 3>> sites;
  for (long i = -reach; i <= reach; ++i)
    for (long j = -reach; j <= reach; ++j)
    {
      const double ij = double(i * i + j * j);
      if (ij > outer * outer)
        continue;
      for (long k = -reach; k <= reach; ++k)
      {
        const double r2 = ij + double(k * k);
        if (r2 >= inner * inner && r2 <= outer * outer)
          sites.push_back({i, j, k});
      }
    }
  std::shuffle(sites.begin(), sites.end(), rng);
  if (sites.size() > n)
    sites.resize(n);
  Points p;
  p.reserve(3 * sites.size());
  for (const auto& s : sites)
    p.insert(p.end(), {s[0] + jitter(rng), s[1] + jitter(rng), s[2] + jitter(rng)});
  return p;
}

Points boxBoundary(std::size_t n)
{
  // Nodes per edge in proportion to the sides 1, 0.8, 0.6, whose faces hold 3.76 side^2 of area.
  const double k = std::sqrt(double(n) / 3.76);
  const double side[3] = {1.0, 0.8, 0.6};
  long m[3];
  for (int a = 0; a < 3; ++a)
    m[a] = std::max(2L, std::lround(k * side[a]) + 1);
  auto at = [&](int a, long i) { return side[a] * double(i) / double(m[a] - 1); }; // as linspace
  Points p;
  for (long i = 0; i < m[0]; ++i)
    for (long j = 0; j < m[1]; ++j)
    {
      const bool edge = i == 0 || i == m[0] - 1 || j == 0 || j == m[1] - 1;
      for (long l = 0; l < m[2]; l += edge ? 1 : m[2] - 1)
        p.insert(p.end(), {at(0, i), at(1, j), at(2, l)});
    }
  return p;
}

Points surfaceOfRevolution(std::size_t n)
{
  // A vase: rings at equally spaced heights, each of equally spaced angles (a revolved CAD part).
  const long rings = std::max(3L, std::lround(std::sqrt(double(n) / 4)));
  const long around = std::max(3L, static_cast<long>(n) / rings);
  Points p;
  p.reserve(3 * std::size_t(rings * around));
  for (long k = 0; k < rings; ++k)
  {
    const double z = double(k) / double(rings - 1);
    const double r = 0.5 + 0.15 * std::sin(3 * z) + 0.1 * z * z;
    for (long j = 0; j < around; ++j)
    {
      const double t = 2 * M_PI * double(j) / double(around);
      p.insert(p.end(), {r * std::cos(t), r * std::sin(t), z});
    }
  }
  return p;
}

Points extrusion(std::size_t n)
{
  // A cam profile, equally spaced in angle, copied at equally spaced heights (an extruded part).
  const long around = std::max(3L, std::lround(2 * std::sqrt(double(n))));
  const long layers = std::max(2L, static_cast<long>(n) / around);
  Points p;
  p.reserve(3 * std::size_t(around * layers));
  for (long k = 0; k < layers; ++k)
  {
    const double z = 0.5 * double(k) / double(layers - 1);
    for (long j = 0; j < around; ++j)
    {
      const double t = 2 * M_PI * double(j) / double(around);
      const double r = 1 + 0.3 * std::cos(3 * t);
      p.insert(p.end(), {r * std::cos(t), r * std::sin(t), z});
    }
  }
  return p;
}

Points parallelPlanes(std::size_t n, std::uint64_t seed)
{
  // Floors of a scanned building: uniform points on three planes.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double heights[3] = {0.0, 0.37, 1.1};
  Points p;
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
    p.insert(p.end(), {u(rng), u(rng), heights[i % 3]});
  return p;
}

Points latitudeLongitude(std::size_t n)
{
  // Rings of latitude, each with the same longitudes, and both poles once (a global grid).
  const long latitudes = std::max(3L, std::lround(std::sqrt(double(n) / 2)));
  const long longitudes = std::max(3L, static_cast<long>(n) / latitudes);
  Points p = {0, 0, 1, 0, 0, -1};
  for (long i = 1; i < latitudes; ++i)
  {
    const double theta = M_PI * double(i) / double(latitudes);
    for (long j = 0; j < longitudes; ++j)
    {
      const double phi = 2 * M_PI * double(j) / double(longitudes);
      p.insert(p.end(),
        {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  return p;
}

Points ellipsoidSurface(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  Points p;
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::array<double, 3> d = randomDirection(rng);
    p.insert(p.end(), {d[0], 0.7 * d[1], 0.4 * d[2]});
  }
  return p;
}

// Uniform by area: directions uniform on the sphere, each kept with a probability proportional to
// the area element of its image on the ellipsoid.
Points ellipsoid(std::size_t n, const std::array<double, 3>& axes, bool latLong, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double a = axes[0], b = axes[1], c = axes[2];
  const double largest = std::max({b * c, a * c, a * b});
  Points p;
  p.reserve(3 * n);
  while (p.size() < 3 * n)
  {
    if (latLong)
    {
      const double colatitude = M_PI * unit(rng), longitude = 2 * M_PI * unit(rng);
      p.insert(p.end(),
        {a * std::sin(colatitude) * std::cos(longitude),
          b * std::sin(colatitude) * std::sin(longitude), c * std::cos(colatitude)});
      continue;
    }
    const std::array<double, 3> d = randomDirection(rng);
    const double area = std::sqrt(
      b * c * d[0] * b * c * d[0] + a * c * d[1] * a * c * d[1] + a * b * d[2] * a * b * d[2]);
    if (unit(rng) * largest <= area)
      p.insert(p.end(), {a * d[0], b * d[1], c * d[2]});
  }
  return p;
}

const std::vector<std::string>& pointSetNames()
{
  static const std::vector<std::string> names = {"cube", "ball", "sphere", "lattice", "clusters",
    "slab", "torus", "cylinder", "noisyshell", "scans", "terrain", "molshell", "boxboundary",
    "revolution", "extrusion", "planes", "latlong", "ellipsoid", "prolate", "prolate-latlong",
    "oblate", "oblate-latlong", "triaxial", "triaxial-latlong"};
  return names;
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
  if (kind == "cylinder")
    return cylinderSurface(n, seed);
  if (kind == "noisyshell")
    return noisySphereShell(n, seed);
  if (kind == "scans")
    return overlappingScans(n, seed);
  if (kind == "boxboundary")
    return boxBoundary(n);
  if (kind == "revolution")
    return surfaceOfRevolution(n);
  if (kind == "extrusion")
    return extrusion(n);
  if (kind == "planes")
    return parallelPlanes(n, seed);
  if (kind == "latlong")
    return latitudeLongitude(n);
  if (kind == "ellipsoid")
    return ellipsoidSurface(n, seed);
  // Smooth closed surfaces of several aspect ratios, each sampled by area and by latitude and
  // longitude: a cigar (4:1:1, its poles at the ends of the long axis), a lentil (8:8:1, poles
  // at the flat faces' centres) and a pebble (1:0.6:0.3).
  if (kind == "prolate" || kind == "prolate-latlong")
    return ellipsoid(n, {0.25, 0.25, 1}, kind != "prolate", seed);
  if (kind == "oblate" || kind == "oblate-latlong")
    return ellipsoid(n, {1, 1, 0.125}, kind != "oblate", seed);
  if (kind == "triaxial" || kind == "triaxial-latlong")
    return ellipsoid(n, {1, 0.6, 0.3}, kind != "triaxial", seed);
  if (kind == "terrain")
    return lidarTerrain(n, seed);
  if (kind == "molshell")
    return molecularShell(n, seed);
  throw std::invalid_argument("unknown point set: " + kind);
}

std::vector<std::uint32_t> firstCopies(const Points& p)
{
  std::map<std::array<double, 3>, std::uint32_t> first;
  std::vector<std::uint32_t> copy(p.size() / 3);
  for (std::uint32_t i = 0; i < copy.size(); ++i)
    copy[i] =
      first.emplace(std::array<double, 3>{p[3 * i], p[3 * i + 1], p[3 * i + 2]}, i).first->second;
  return copy;
}

Points scaled(Points p, double factor, double offset)
{
  for (double& x : p)
    x = x * factor + offset;
  return p;
}

Points joined(Points a, const Points& b)
{
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

} // namespace fd3test
