// The kernel's entry point: clean and normalize the points, order them, insert them one by one,
// and hand back the finite tetrahedra with input point ids.
#include "InsertionOrder.h"
#include "Triangulator.h"
#include "fd3/Delaunay.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <utility>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fd3
{
namespace
{
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// An exact change of coordinates x -> (x - shift) * scale that brings the points into [-1, 1],
/// so that no predicate overflows (1e300) or underflows (1e-300). The scale is a power of two and a
/// shift is used on an axis only when every subtraction on it is exact (clouds far from the
/// origin, where it saves the float filter from cancellation), so predicates keep their signs.
struct Normalization
{
  double shift[3] = {0, 0, 0};
  double scale = 1.0;

  Normalization(const double* xyz, const std::vector<std::uint32_t>& ids, const Box& box)
  {
    double extent = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double center = box.lo[a] + box.extent(a) / 2;
      bool exact = std::isfinite(center);
      for (std::size_t i = 0; i < ids.size() && exact; ++i)
      {
        double diff, err;
        twoDiff(xyz[3 * std::size_t(ids[i]) + a], center, diff, err);
        exact = err == 0.0;
      }
      shift[a] = exact ? center : 0.0;
      extent = std::max({extent, std::fabs(box.lo[a] - shift[a]), std::fabs(box.hi[a] - shift[a])});
    }
    int exponent = 0;
    std::frexp(extent, &exponent);
    scale = extent > 0 ? std::ldexp(1.0, -exponent) : 1.0;
  }

  void apply(const double* p, double* out) const
  {
    for (int a = 0; a < 3; ++a)
      out[a] = (p[a] - shift[a]) * scale;
  }
  Box apply(const Box& box) const
  {
    Box out;
    apply(box.lo, out.lo);
    apply(box.hi, out.hi);
    return out;
  }
};

/// Moves the first four affinely independent points of `order` to its front, keeping the rest in
/// order. Returns false when there are none (fewer than 4 distinct points, or all coplanar).
bool moveFirstTetrahedronToFront(
  const double* xyz, const Normalization& norm, std::vector<std::uint32_t>& order)
{
  Predicates predicates;
  double p[4][3];
  std::size_t found[4] = {0, 0, 0, 0};
  int have = 1;
  norm.apply(xyz + 3 * std::size_t(order[0]), p[0]);
  for (std::size_t i = 1; i < order.size() && have < 4; ++i)
  {
    norm.apply(xyz + 3 * std::size_t(order[i]), p[have]);
    bool independent = false;
    if (have == 1)
      independent = p[1][0] != p[0][0] || p[1][1] != p[0][1] || p[1][2] != p[0][2];
    else if (have == 2)
      independent = !predicates.collinear(p[0], p[1], p[2]);
    else
      independent = predicates.orient3d(p[0], p[1], p[2], p[3]) != 0;
    if (independent)
      found[have++] = i;
  }
  if (have < 4)
    return false;
  std::uint32_t first[4];
  for (int k = 0; k < 4; ++k)
    first[k] = order[found[k]];
  for (int k = 3; k >= 1; --k) // erase from the back so earlier positions stay valid
    order.erase(order.begin() + static_cast<std::ptrdiff_t>(found[k]));
  order.erase(order.begin());
  order.insert(order.begin(), first, first + 4);
  return true;
}

/// The live finite tetrahedra with input point ids, compacted in place inside the mesh's records
/// (tetrahedron k's vertices go to words 4k..4k+3 of record t >= k, never ahead of what is still
/// to be read), and, when asked for, their neighbours renumbered.
void extractOutput(TetMesh& mesh, const std::vector<std::uint32_t>& inputId, bool withNeighbors,
  Triangulation& out)
{
  const std::size_t slots = mesh.slots();
  constexpr std::uint32_t kDropped = 0xFFFFFFFFu; // dead or ghost: not in the output
  std::vector<std::uint32_t> newId;
  if (withNeighbors)
  {
    newId.assign(slots, kDropped);
    std::uint32_t kept = 0;
    for (TetId t = 0; t < slots; ++t)
      if (!mesh.isDead(t) && !mesh.isGhost(t))
        newId[t] = kept++;
    out.neighbors.resize(4 * std::size_t(kept));
    for (TetId t = 0; t < slots; ++t)
      if (const std::uint32_t k = newId[t]; k != kDropped)
        for (int f = 0; f < 4; ++f)
        {
          const FaceCode code = mesh.neighbor(t, f);
          const std::uint32_t n = newId[tetOf(code)];
          out.neighbors[4 * std::size_t(k) + f] = n == kDropped ? kNoNeighbor : faceCode(n, faceOf(code));
        }
    std::vector<std::uint32_t>().swap(newId);
  }
  IdArray records = mesh.takeRecords();
  std::size_t kept = 0;
  for (std::size_t t = 0; t < slots; ++t)
  {
    const std::uint32_t* r = &records[8 * t];
    if ((r[0] >> kVertexIdBits) == kDead || r[3] == kInfinite)
      continue;
    const std::uint32_t v[4] = {r[0] & (kMaxVertices - 1), r[1], r[2], r[3]};
    for (int i = 0; i < 4; ++i)
      records[4 * kept + i] = inputId[v[i]];
    ++kept;
  }
  records.resize(4 * kept);
  out.tetrahedra = std::move(records);
}

} // namespace

Triangulation triangulate(const double* xyz, std::size_t count, const Options& options)
{
  const auto start = Clock::now();
  Triangulation out;
  Statistics& stats = out.stats;
  stats.inputPoints = count;

  std::vector<std::uint32_t> ids;
  ids.reserve(count);
  Box box;
  for (std::size_t i = 0; i < count; ++i)
  {
    if (!isFinite(xyz + 3 * i))
      continue;
    if (ids.empty())
      box = Box::around(xyz + 3 * i);
    box.include(xyz + 3 * i);
    ids.push_back(static_cast<std::uint32_t>(i));
  }
  stats.nonFinitePoints = count - ids.size();
  if (ids.empty())
  {
    out.status = Status::Empty;
    return out;
  }
  if (ids.size() >= kMaxVertices)
    throw std::length_error("fd3::triangulate: more than 2^30 points");

  const Normalization norm(xyz, ids, box);
  std::vector<std::uint16_t> key(count);
  for (const std::uint32_t id : ids)
    key[id] = perturbationKey(xyz + 3 * std::size_t(id), options.randomSeed);
  InsertionPlan plan =
    planInsertion(xyz, key.data(), std::move(ids), box, options.order, options.randomSeed);
  stats.duplicatesMerged = plan.duplicates.size();
  std::vector<std::uint32_t>& order = plan.order;
  const auto skipped = skipClosePoints(xyz, plan, options.tolerance);
  stats.closePointsSkipped = skipped.size();
  if (!moveFirstTetrahedronToFront(xyz, norm, order))
  {
    out.status = order.size() < 4 ? Status::TooFewPoints : Status::Degenerate;
    stats.secondsTotal = secondsSince(start);
    return out;
  }
  // The input read in insertion order, which jumps around it: the point a few places ahead is
  // requested early.
  constexpr std::size_t kAhead = 16;
  VertexArray vertices(order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    if (i + kAhead < order.size())
      prefetch(xyz + 3 * std::size_t(order[i + kAhead]));
    norm.apply(xyz + 3 * std::size_t(order[i]), vertices[i].xyz);
    vertices[i].localNumber = Vertex::kNoLocal;
    vertices[i].key = key[order[i]];
  }
  std::vector<std::uint16_t>().swap(key);
  stats.secondsSort = secondsSince(start);
#if defined(__GLIBC__)
  // The sort's large scratch buffers were freed, but glibc keeps such memory in its heap once its
  // mmap threshold has grown; hand it back before the mesh grows so it does not add to the peak.
  malloc_trim(0);
#endif

  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = options.volumeThreshold > 0 ? 1 : (options.threads > 0 ? options.threads : hardware);
  Triangulator triangulator(std::move(vertices), norm.apply(box), options, threads);
  if (!triangulator.insertAll(plan.roundStarts, options.progress))
  {
    out.status = Status::Aborted;
    return out;
  }
  {
    const Statistics inserted = triangulator.statistics();
    stats.insertedPoints = inserted.insertedPoints;
    stats.walkSteps = inserted.walkSteps;
    stats.maxWalkSteps = inserted.maxWalkSteps;
    stats.cavityTetrahedra = inserted.cavityTetrahedra;
    stats.deferredInsertions = inserted.deferredInsertions;
    stats.secondsLocate = inserted.secondsLocate;
    stats.secondsCavity = inserted.secondsCavity;
    stats.secondsFill = inserted.secondsFill;
    triangulator.addPredicateCounts(stats);
  }
#ifndef NDEBUG
  constexpr bool kDebugBuild = true;
#else
  constexpr bool kDebugBuild = false;
#endif
  if (options.checkMesh || kDebugBuild)
  {
    out.checkReport = triangulator.checkMesh();
    if (!out.checkReport.empty())
    {
      out.status = Status::CheckFailed;
      return out;
    }
  }

  const auto outputStart = Clock::now();
  extractOutput(triangulator.releaseWorkspace(), order, options.computeNeighbors, out);
  out.representative.assign(count, kNoPoint);
  for (std::uint32_t id : order)
    out.representative[id] = id;
  for (const auto& [point, near] : skipped)
    out.representative[point] = near;
  for (const auto& [copy, original] : plan.duplicates)
    out.representative[copy] = out.representative[original];
  stats.tetrahedra = out.numberOfTetrahedra();
  stats.secondsOutput = secondsSince(outputStart);
  stats.secondsTotal = secondsSince(start);
  return out;
}

const char* toString(Status status)
{
  switch (status)
  {
    case Status::Ok:
      return "ok";
    case Status::Empty:
      return "no finite input point";
    case Status::TooFewPoints:
      return "fewer than 4 distinct points";
    case Status::Degenerate:
      return "all points are collinear or coplanar";
    case Status::Aborted:
      return "aborted";
    case Status::CheckFailed:
      return "the kernel's mesh check failed (a bug; please report it)";
  }
  return "unknown";
}

} // namespace fd3
