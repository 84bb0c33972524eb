// The cost of the predicates' hard cases, in nanoseconds a call, beside the calls the float filter
// decides: an insphere test that is exactly zero (a tie) with the symbolic perturbation that breaks
// it, an insphere test within rounding of zero but not zero (the exact stage decides), and an
// orientation that is exactly zero. The points are what structured surface samples give the
// kernel, in its frame ([-1, 1]): the corners of cells of a structured grid's face (exact
// rectangles, so exactly cocircular and coplanar, at linspace coordinates, on no small integer
// grid), and nodes of a latitude-longitude grid (cospherical but for the rounding of cos and sin).
//
//   PredicateCost [calls per case, default 4000000]
#include "exact/Predicates.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

namespace
{
using Point = std::array<double, 3>;

/// A tetrahedron, positively oriented, and a fifth point.
struct Query
{
  Point p[4];
  Point e;
};

/// Cells of the face z = z0 of a structured grid over [-0.9, 0.9]^3 (m nodes an edge): the
/// tetrahedron of three corners and the node above the first, and the fourth corner, which lies
/// on the tetrahedron's sphere and in the plane of its first three vertices.
std::vector<Query> gridCells(int m, std::size_t count, std::mt19937_64& rng)
{
  auto node = [m](int i) { return -0.9 + 1.8 * double(i) / double(m - 1); };
  std::uniform_int_distribution<int> pick(0, m - 2);
  std::vector<Query> out(count);
  for (Query& q : out)
  {
    const int i = pick(rng), j = pick(rng), l = pick(rng);
    q.p[0] = {node(i), node(j), node(l)};
    q.p[1] = {node(i + 1), node(j), node(l)};
    q.p[2] = {node(i), node(j + 1), node(l)};
    q.p[3] = {node(i), node(j), node(l + 1)};
    q.e = {node(i + 1), node(j + 1), node(l)};
  }
  return out;
}

/// Five neighbouring nodes of a latitude-longitude grid on the sphere of radius 0.9.
std::vector<Query> sphereNodes(int latitudes, std::size_t count, std::mt19937_64& rng)
{
  const int longitudes = 2 * latitudes;
  auto node = [&](int i, int j) {
    const double theta = M_PI * double(i) / double(latitudes);
    const double phi = 2 * M_PI * double(j) / double(longitudes);
    return Point{0.9 * std::sin(theta) * std::cos(phi), 0.9 * std::sin(theta) * std::sin(phi),
      0.9 * std::cos(theta)};
  };
  std::uniform_int_distribution<int> lat(1, latitudes - 3), lon(0, longitudes - 2);
  std::vector<Query> out(count);
  for (Query& q : out)
  {
    const int i = lat(rng), j = lon(rng);
    q.p[0] = node(i, j);
    q.p[1] = node(i, j + 1);
    q.p[2] = node(i + 1, j);
    q.p[3] = node(i + 2, j + 1);
    q.e = node(i + 1, j + 1);
  }
  return out;
}

/// Random points in [-0.9, 0.9]^3: the float filter decides nearly every call.
std::vector<Query> uniform(std::size_t count, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  std::vector<Query> out(count);
  for (Query& q : out)
  {
    for (Point& p : q.p)
      p = {u(rng), u(rng), u(rng)};
    q.e = {u(rng), u(rng), u(rng)};
  }
  return out;
}

/// Orders each tetrahedron positively (drops the flat ones).
void orient(std::vector<Query>& queries, fd3::Predicates& predicates)
{
  std::vector<Query> kept;
  for (Query q : queries)
  {
    const int sign =
      predicates.orient3d(q.p[0].data(), q.p[1].data(), q.p[2].data(), q.p[3].data());
    if (sign < 0)
      std::swap(q.p[1], q.p[2]);
    if (sign != 0)
      kept.push_back(q);
  }
  queries.swap(kept);
}

fd3::Predicates tunedTo(const std::vector<Query>& queries)
{
  std::vector<double> xyz;
  for (const Query& q : queries)
  {
    for (const Point& p : q.p)
      xyz.insert(xyz.end(), p.begin(), p.end());
    xyz.insert(xyz.end(), q.e.begin(), q.e.end());
  }
  fd3::Bounds box;
  for (int a = 0; a < 3; ++a)
  {
    box.lo[a] = -1;
    box.hi[a] = 1;
  }
  fd3::Predicates predicates;
  predicates.adaptTo(xyz.data(), xyz.size() / 3, 3, box);
  return predicates;
}

/// Nanoseconds per call of `call` over `calls` calls cycling through the queries, best of 3.
template <typename Call>
double nanoseconds(const std::vector<Query>& queries, std::size_t calls, Call&& call, long& sink)
{
  double best = HUGE_VAL;
  for (int round = 0; round < 3; ++round)
  {
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t k = 0; k < calls; ++k)
      sink += call(queries[k % queries.size()]);
    const std::chrono::duration<double, std::nano> took = std::chrono::steady_clock::now() - start;
    best = std::min(best, took.count() / double(calls));
  }
  return best;
}

int inSphere(fd3::Predicates& predicates, const Query& q)
{
  const double* p[4] = {q.p[0].data(), q.p[1].data(), q.p[2].data(), q.p[3].data()};
  return predicates.insideSoS(p, q.e.data());
}

int exactInSphere(fd3::Predicates& predicates, const Query& q)
{
  return predicates.inSphere(
    q.p[0].data(), q.p[1].data(), q.p[2].data(), q.p[3].data(), q.e.data());
}

void report(const char* what, std::vector<Query> queries, std::size_t calls, bool orientation)
{
  fd3::Predicates predicates = tunedTo(queries);
  orient(queries, predicates);
  int zeros = 0;
  for (const Query& q : queries)
    zeros +=
      (orientation ? predicates.orient3d(q.p[0].data(), q.p[1].data(), q.p[2].data(), q.e.data())
                   : exactInSphere(predicates, q)) == 0;
  long sink = 0;
  const double ns = orientation
    ? nanoseconds(
        queries, calls,
        [&](const Query& q) {
          return predicates.orient3d(q.p[0].data(), q.p[1].data(), q.p[2].data(), q.e.data());
        },
        sink)
    : nanoseconds(
        queries, calls, [&](const Query& q) { return inSphere(predicates, q); }, sink);
  std::printf("| %s | %s | %.0f%% | %.1f |\n", what, orientation ? "orient3d" : "insphere + SoS",
    100.0 * zeros / double(queries.size()), ns);
  if (sink == 42)
    std::printf(" ");
}
} // namespace

int main(int argc, char* argv[])
{
  const std::size_t calls = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 4000000;
  std::mt19937_64 rng(1);
  constexpr std::size_t kQueries = 4096; // distinct configurations, cycled
  std::printf("| points | predicate | exactly zero | ns a call |\n|---|---|---:|---:|\n");
  report("uniform", uniform(kQueries, rng), calls, false);
  report("uniform", uniform(kQueries, rng), calls, true);
  report("structured grid cell (tie)", gridCells(1001, kQueries, rng), calls, false);
  report("latitude-longitude nodes (near tie)", sphereNodes(500, kQueries, rng), calls, false);
  report("structured grid cell (coplanar)", gridCells(1001, kQueries, rng), calls, true);
  return 0;
}
