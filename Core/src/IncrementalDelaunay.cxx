// The kernel's entry points: clean and normalize the points, order them, insert them, and hand
// back the finite tetrahedra with input point ids; triangulate() runs an IncrementalDelaunay once.
#include "FiniteBounds.h"
#include "derived/Halo.h"
#include "exact/Frame.h"
#include "fd3/Distributed.h"
#include "insertion/InsertionOrder.h"
#include "insertion/Triangulator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <utility>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fd3
{
namespace
{
using Clock = std::chrono::steady_clock;
/// Perturbation keys by point id (only finite points' are written and read).
using Keys = std::vector<std::uint16_t, BulkAllocator<std::uint16_t>>;
/// How far ahead a loop that reads records out of their order fetches them: enough to cover a
/// miss to memory.
constexpr std::size_t kFetchAhead = 16;

double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The scale of residuals in `frame`: exact where the frame holds them (PeriodicDelaunay chose it
/// so).
double residualScale(const Frame& frame)
{
  return frame.identity ? 1.0 : frame.scale;
}

/// Moves the first four affinely independent points of `order` to its front, keeping the rest in
/// order. Returns false when there are none (fewer than 4 distinct points, or all coplanar).
/// `images`, where given, are the points' periodic images (by point id, in the input's units).
bool moveFirstTetrahedronToFront(
  const double* xyz, const Frame& frame, IdArray& order, const ImageOf* images)
{
  Predicates predicates;
  if (frame.identity)
    predicates.allowAnyMagnitude();
  double p[4][3];
  // Periodic images: the four candidates' own, in the frame, for the exact stage.
  PeriodicImages candidates;
  if (images)
  {
    for (int k = 0; k < 4; ++k)
      candidates.append(images[order[0]]);
    candidates.locate(p[0], 3);
    predicates.useImages(&candidates);
  }
  auto take = [&](std::size_t i, int k) {
    toFrame(frame, xyz + 3 * std::size_t(order[i]), p[k]);
    if (images)
    {
      ImageOf& image = candidates.at(k);
      image = images[order[i]];
      for (double& r : image.residual)
        r *= residualScale(frame);
    }
  };
  std::size_t found[4] = {0, 0, 0, 0};
  int have = 1;
  take(0, 0);
  for (std::size_t i = 1; i < order.size() && have < 4; ++i)
  {
    take(i, have);
    bool independent = false;
    if (have == 1) // distinct points, as the records of images are too
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
  // Only the stretch up to the last one found moves: the others in it go back by as many places
  // as found ones follow them, from the back.
  std::size_t write = found[3];
  for (std::size_t i = found[3] + 1, k = 3; i-- > 0;)
  {
    if (k < 4 && i == found[k])
    {
      --k; // wraps past 0 once all four are passed
      continue;
    }
    order[write--] = order[i];
  }
  std::copy(first, first + 4, order.begin());
  return true;
}

/// The live finite tetrahedra of `records` (a mesh's, `slots` of them) with input point ids
/// (`pointOf`, by vertex rank), compacted in place, and, when asked for, their neighbours
/// renumbered. Tetrahedron k's vertices go to words 4k..4k+3, inside record k/2 <= t/2 for its
/// slot t: the slots of [a, 2a) write only into records below a, which the slots before a have
/// been read from, so each such range is compacted on every thread at once, one after another.
void extractOutput(IdArray records, std::size_t slots, const std::uint32_t* pointOf,
  bool withNeighbors, Triangulation& out, ThreadTeam& team)
{
  constexpr std::uint32_t kDropped = 0xFFFFFFFFu; // dead or ghost: not in the output
  auto kept = [&](std::size_t t) {
    return (records[8 * t] >> kVertexIdBits) != kDead && records[8 * t + 3] != kInfinite;
  };
  auto countKept = [&](std::size_t begin, std::size_t end) {
    std::size_t count = 0;
    for (std::size_t t = begin; t < end; ++t)
      count += kept(t);
    return count;
  };
  ThreadedWork& record = team.newRecord("output");
  if (withNeighbors)
  {
    std::vector<std::uint32_t> newId(slots);
    std::size_t count = 0;
    team.countThenWrite(record, 0, slots, count, countKept,
      [&](std::size_t, std::size_t begin, std::size_t end, std::size_t next) {
        for (std::size_t t = begin; t < end; ++t)
          newId[t] = kept(t) ? static_cast<std::uint32_t>(next++) : kDropped;
        return next;
      });
    out.neighbors.resize(4 * count);
    const std::size_t parts = team.partsFor(slots);
    team.run(
      parts,
      [&](std::size_t k) {
        const Part part = partOf(slots, k, parts);
        for (std::size_t t = part.first; t < part.last; ++t)
          if (const std::uint32_t id = newId[t]; id != kDropped)
            for (int f = 0; f < 4; ++f)
            {
              const FaceCode code = records[8 * t + 4 + f];
              const std::uint32_t n = newId[tetOf(code)];
              out.neighbors[4 * std::size_t(id) + f] =
                n == kDropped ? kNoNeighbor : faceCode(n, faceOf(code));
            }
      },
      record);
  }
  std::size_t count = 0;
  for (std::size_t a = 0, b = 1; a < slots; a = b, b = 2 * b)
    team.countThenWrite(record, a, std::min(b, slots), count, countKept,
      [&](std::size_t, std::size_t begin, std::size_t end, std::size_t next) {
        for (std::size_t t = begin; t < end; ++t)
        {
          if (!kept(t))
            continue;
          const std::uint32_t v[4] = {records[8 * t] & (kMaxVertices - 1), records[8 * t + 1],
            records[8 * t + 2], records[8 * t + 3]};
          for (int i = 0; i < 4; ++i)
            records[4 * next + i] = pointOf[v[i]];
          ++next;
        }
        return next;
      });
  records.resize(4 * count);
  // The compacted tetrahedra take half of the records' 32 bytes or less: the rest is given back
  // before the caller converts them (the VTK filter's peak).
  team.releaseSpareCapacity(records, "output");
  out.tetrahedra = std::move(records);
}

/// The weights of points at one position (plan.duplicates' groups): only the heaviest can be a
/// vertex, so it takes the group's place in the order (the smallest id among equals). The others
/// of its weight stay its duplicates; the lighter ones are hidden, appended to `hidden`. Periodic
/// images (`images`, by id) with one record may lie at different exact places: those stay
/// duplicates whatever their weights, for the caller to tell apart (IncrementalDelaunay::
/// ofImages()).
void keepHeaviestAtEachPosition(const double* weights, const ImageOf* images, InsertionPlan& plan,
  std::vector<std::uint32_t>& hidden)
{
  std::unordered_map<std::uint32_t, std::uint32_t> heaviest; // by original
  for (const auto& [copy, original] : plan.duplicates)
  {
    auto [entry, first] = heaviest.try_emplace(original, original);
    if (weights[copy] > weights[entry->second] ||
      (weights[copy] == weights[entry->second] && copy < entry->second))
      entry->second = copy;
  }
  if (heaviest.empty())
    return;
  for (std::uint32_t& id : plan.order)
    if (const auto found = heaviest.find(id); found != heaviest.end())
      id = found->second;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> duplicates;
  auto samePlace = [images](std::uint32_t a, std::uint32_t b) {
    return !images || std::equal(images[a].residual, images[a].residual + 3, images[b].residual);
  };
  auto place = [&](std::uint32_t member, std::uint32_t kept) {
    if (member == kept)
      return;
    if (weights[member] == weights[kept] || !samePlace(member, kept))
      duplicates.emplace_back(member, kept);
    else
      hidden.push_back(member);
  };
  for (const auto& [original, kept] : heaviest)
    place(original, kept);
  for (const auto& [copy, original] : plan.duplicates)
    place(copy, heaviest[original]);
  plan.duplicates = std::move(duplicates);
}

int threadCount(const Options& options)
{
  if (options.volumeThreshold > 0)
    return 1; // which slivers the guard avoids depends on the order of insertion
  return boundedThreads(options.threads);
}

/// The point ids and frame coordinates of `n` vertices of tetrahedron t, those at `local`.
void vertexRecords(const TetMesh& mesh, const VertexArray& vertices, TetId t, const int* local,
  int n, std::uint32_t* ids, const double** xyz)
{
  for (int i = 0; i < n; ++i)
  {
    const Vertex& vertex = vertices[mesh.vertex(t, local[i])];
    ids[i] = vertex.point;
    xyz[i] = vertex.xyz;
  }
}
} // namespace

struct IncrementalDelaunay::Impl
{
  Options options;
  Frame frame;
  bool frameGiven = true; // else made from the first batch's bounds (triangulate())
  Status status = Status::Ok;
  bool released = false;  // release() handed the records out: nothing is left to add to
  Statistics stats;       // the figures of every batch; the inserters' are added on output
  std::size_t points = 0; // point ids handed out
  std::size_t room = 0;   // vertex records reserved beyond the first batch's
  // (point, point it was skipped for), then (duplicate, original): the order representatives
  // are resolved in.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> skipped, duplicates;
  std::unique_ptr<ThreadTeam> team; // records the threaded work of every batch
  std::unique_ptr<Triangulator> triangulator;
  // The input coordinates the mesh holds: those of the points from id heldFrom on. That is every
  // point until the mesh starts. After that, a mesh that reads its points holds none (the caller
  // keeps them), and one that takes them holds them all, except a first batch that the vertex
  // records give back bit for bit (recoverable()): that batch is freed once the records are
  // made, and its non-finite points, which have no record, are set aside.
  bool takesPoints = false;
  Coordinates held;
  std::size_t heldFrom = 0;
  std::vector<std::pair<std::uint32_t, std::array<double, 3>>> aside;
  // Weighted points: the weights of the batch at hand, by its point ids; whether the mesh is
  // weighted (triangulate() leaves it unweighted where every weight is the same); the weights of
  // the held points while the mesh has not started; the points hidden before insertion, lighter
  // than another at their position.
  const double* weights = nullptr;
  bool weighted = false;
  std::vector<double> heldWeights;
  std::vector<std::uint32_t> hiddenCopies;
  // A periodic mesh (ofImages()): the images of the batch at hand, by its point ids, in the
  // input's units; null for a batch of points that are no images, and on any other mesh.
  const ImageOf* images = nullptr;

  /// The options and, for a weighted mesh, the first batch's weights.
  void takeOptions(const Options& givenOptions, const double* givenWeights);
  /// The first batch, in a frame given by the caller.
  void start(const double* xyz, std::size_t count, const Options& givenOptions,
    const Frame& givenFrame, std::size_t givenRoom, const double* givenWeights);
  void insertFirst(const double* xyz, std::size_t count);
  void insertMore(const double* xyz, std::size_t count, const double* moreWeights);
  bool insertOne(const double* p, MeshChange& change);
  /// The output; with `release`, the mesh's records go into it, which ends the mesh, and with
  /// `xyz` too, the coordinates of every point go there (IncrementalDelaunay::release(xyz)).
  Triangulation output(bool release, Coordinates* xyz = nullptr);
  /// The input coordinates of point `id` where the mesh holds them, else null.
  const double* heldPoint(std::size_t id) const;
  /// For each point id, its vertex; kNoVertex for a point that is not one.
  std::vector<VertId> vertexOfPoint() const;

private:
  /// Frees the held first batch where the vertex records give it back (see `held`).
  void freeRecoverablePoints();
  void giveBackPoints(Coordinates& xyz);
  /// The input coordinates of every vertex and exact duplicate, as the records give them back.
  void writeRecordedPoints(double* xyz) const;
  /// The finite ones of `count` points, as point ids, and their bounding box.
  IdArray finitePoints(const double* xyz, std::size_t count, Bounds& box);
  /// The keys of the perturbation's order for `ids`, indexed by point id (local to xyz).
  Keys keys(const double* xyz, std::size_t count, const IdArray& ids) const;
  /// Weighted: the weights of `order` (point ids of the batch at hand) in the frame; else none.
  std::vector<double> framedWeights(const IdArray& order) const;
  /// The images of `order` (point ids of the batch at hand), their residuals in the frame (exact:
  /// the periodic driver chose a frame that scales every residual exactly); none for a batch
  /// without images.
  std::vector<ImageOf> framedImages(const IdArray& order) const;
  /// Vertex records of `order` (point ids, local to xyz, whose first is point id `firstPoint`) in
  /// the frame, with capacity for `extra` more.
  VertexArray vertices(
    const double* xyz, const IdArray& order, std::size_t firstPoint, std::size_t extra);
};

IdArray IncrementalDelaunay::Impl::finitePoints(const double* xyz, std::size_t count, Bounds& box)
{
  if (points + count >= kMaxVertices)
    throw std::length_error("fd3::triangulate: more than 2^30 points");
  IdArray ids;
  box = finiteBounds(*team, "sort", xyz, count, &ids);
  if (weights)
    ids.erase(std::remove_if(ids.begin(), ids.end(),
                [&](std::uint32_t id) { return !std::isfinite(weights[id]); }),
      ids.end());
  stats.inputPoints += count;
  stats.nonFinitePoints += count - ids.size();
  return ids;
}

Keys IncrementalDelaunay::Impl::keys(const double* xyz, std::size_t count, const IdArray& ids) const
{
  // From the coordinates in the frame, as the predicates compute them on a tie.
  Keys key(count);
  team->forRanges(ids.size(), "sort", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      double p[3];
      toFrame(frame, xyz + 3 * std::size_t(ids[i]), p);
      key[ids[i]] = perturbationKey(p, options.randomSeed);
    }
  });
  return key;
}

std::vector<double> IncrementalDelaunay::Impl::framedWeights(const IdArray& order) const
{
  if (!weighted)
    return {};
  std::vector<double> out(order.size());
  const int twice = frame.identity ? 0 : 2 * std::ilogb(frame.scale);
  // The product by 2^twice, where that is a double, rounds as ldexp() does, which is a library
  // call per weight. Read in insertion order, as vertices() reads the points.
  const bool representable = twice >= std::numeric_limits<double>::min_exponent - 53 &&
    twice < std::numeric_limits<double>::max_exponent;
  const double factor = std::ldexp(1.0, twice);
  team->forRanges(order.size(), "sort", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      if (i + kFetchAhead < end)
        prefetch(weights + order[i + kFetchAhead]);
      const double w = weights[order[i]];
      out[i] = representable ? w * factor : std::ldexp(w, twice);
    }
  });
  return out;
}

std::vector<ImageOf> IncrementalDelaunay::Impl::framedImages(const IdArray& order) const
{
  if (!images)
    return {};
  // Read in insertion order, as vertices() reads the points.
  std::vector<ImageOf> out;
  out.reserve(order.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    if (i + kFetchAhead < order.size())
      prefetch(images + order[i + kFetchAhead]);
    out.push_back(images[order[i]]);
    for (double& r : out.back().residual)
      r *= residualScale(frame);
  }
  return out;
}

VertexArray IncrementalDelaunay::Impl::vertices(
  const double* xyz, const IdArray& order, std::size_t firstPoint, std::size_t extra)
{
  // The input read in insertion order, which jumps around it: the point a few places ahead is
  // requested early.
  VertexArray out;
  out.reserve(order.size() + extra);
  out.resize(order.size());
  team->forRanges(order.size(), "sort", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      if (i + kFetchAhead < end)
        prefetch(xyz + 3 * std::size_t(order[i + kFetchAhead]));
      toFrame(frame, xyz + 3 * std::size_t(order[i]), out[i].xyz);
      out[i].tet = kNoTet;
      out[i].point = static_cast<std::uint32_t>(firstPoint + order[i]);
    }
  });
  return out;
}

void IncrementalDelaunay::Impl::insertFirst(const double* xyz, std::size_t count)
{
  const auto start = Clock::now();
  if (!team)
    team = std::make_unique<ThreadTeam>(threadCount(options));
  Bounds box;
  IdArray ids = finitePoints(xyz, count, box);
  points = count;
  if (ids.empty())
  {
    status = Status::Empty;
    return;
  }
  weighted = weights && (frameGiven || std::any_of(ids.begin(), ids.end(), [&](std::uint32_t id) {
    return weights[id] != weights[ids.front()];
  }));
  if (!frameGiven)
    frame = frameWithin(xyz, count, box, team->stretches("sort"));
  if (weighted && !weightsFitFrame(frame, weights, count))
  {
    if (frameGiven)
      throw std::invalid_argument("fd3::IncrementalDelaunay: a weight beyond the frame");
    frame = identityFrame(box);
  }
  Keys key = keys(xyz, count, ids);
  InsertionPlan plan =
    planInsertion(xyz, key.data(), std::move(ids), box, options.order, options.randomSeed, *team);
  hiddenCopies.clear();
  if (weighted)
  {
    keepHeaviestAtEachPosition(weights, images, plan, hiddenCopies);
    stats.hiddenPoints = hiddenCopies.size();
  }
  stats.duplicatesMerged = plan.duplicates.size();
  duplicates = std::move(plan.duplicates);
  skipped = skipClosePoints(xyz, plan, options.tolerance);
  stats.closePointsSkipped = skipped.size();
  if (!moveFirstTetrahedronToFront(xyz, frame, plan.order, images))
  {
    status = plan.order.size() < 4 ? Status::TooFewPoints : Status::Degenerate;
    return;
  }
  status = Status::Ok;
  VertexArray records = vertices(xyz, plan.order, 0, room);
  std::vector<double> vertexWeights = framedWeights(plan.order);
  std::vector<ImageOf> vertexImages = framedImages(plan.order);
  team->release(plan.order, "sort");
  team->release(key, "sort");
  if (takesPoints)
    freeRecoverablePoints(); // xyz, which may be `held`, is not read after this
  stats.secondsSort = secondsSince(start);
#if defined(__GLIBC__)
  // The sort's large scratch buffers were freed, but glibc keeps such memory in its heap once its
  // mmap threshold has grown; hand it back before the mesh grows so it does not add to the peak.
  malloc_trim(0);
#endif
  triangulator = std::make_unique<Triangulator>(std::move(records), toFrame(frame, box), options,
    *team, frame.identity, std::move(vertexWeights));
  if (images)
    triangulator->useImages(std::move(vertexImages));
  if (!triangulator->insertAll(plan.roundStarts, options.progress))
    status = Status::Aborted;
}

void IncrementalDelaunay::Impl::insertMore(
  const double* xyz, std::size_t count, const double* moreWeights)
{
  for (std::size_t i = 0; i < count; ++i)
    if (isFinite(xyz + 3 * i) && !frame.bounds.contains(xyz + 3 * i))
      throw std::invalid_argument("fd3::IncrementalDelaunay::add: a point outside the frame");
  if (!moreWeights != !(weighted || (!triangulator && weights)))
    throw std::logic_error("fd3::IncrementalDelaunay::add: weights go with a weighted mesh only");
  if (moreWeights && !weightsFitFrame(frame, moreWeights, count))
    throw std::invalid_argument("fd3::IncrementalDelaunay::add: a weight beyond the frame");
  if (!triangulator)
  {
    // Not started yet: start again from every point so far, these included.
    held.insert(held.end(), xyz, xyz + 3 * count);
    if (moreWeights)
      heldWeights.insert(heldWeights.end(), moreWeights, moreWeights + count);
    stats = Statistics();
    skipped.clear();
    weights = moreWeights ? heldWeights.data() : nullptr;
    insertFirst(held.data(), held.size() / 3);
    if (triangulator && !takesPoints)
      Coordinates().swap(held);
    if (triangulator)
      std::vector<double>().swap(heldWeights);
    return;
  }
  weights = moreWeights;
  if (takesPoints)
    held.insert(held.end(), xyz, xyz + 3 * count);
  const auto start = Clock::now();
  Bounds box;
  IdArray ids = finitePoints(xyz, count, box);
  if (!ids.empty())
  {
    Keys key = keys(xyz, count, ids);
    InsertionPlan plan =
      planInsertion(xyz, key.data(), std::move(ids), box, options.order, options.randomSeed, *team);
    if (weighted)
    {
      std::vector<std::uint32_t> hidden;
      keepHeaviestAtEachPosition(weights, images, plan, hidden);
      for (const std::uint32_t id : hidden)
        hiddenCopies.push_back(static_cast<std::uint32_t>(id + points));
      stats.hiddenPoints += hidden.size();
    }
    for (const auto& [copy, original] : plan.duplicates)
      duplicates.emplace_back(copy + points, original + points);
    stats.duplicatesMerged += plan.duplicates.size();
    VertexArray more = vertices(xyz, plan.order, points, 0);
    std::vector<double> moreFramed = framedWeights(plan.order);
    const std::vector<ImageOf> moreImages = framedImages(plan.order);
    stats.secondsSort += secondsSince(start);
    if (!triangulator->insertMore(
          std::move(more), std::move(moreFramed), plan.roundStarts, options.progress, moreImages))
      status = Status::Aborted;
  }
  points += count;
}

bool IncrementalDelaunay::Impl::insertOne(const double* p, MeshChange& change)
{
  change.deleted.clear();
  change.made.clear();
  if (isFinite(p) && !frame.bounds.contains(p))
    throw std::invalid_argument("fd3::IncrementalDelaunay::addOne: a point outside the frame");
  if (takesPoints)
    held.insert(held.end(), p, p + 3);
  const auto id = static_cast<std::uint32_t>(points++);
  ++stats.inputPoints;
  if (!isFinite(p))
  {
    ++stats.nonFinitePoints;
    return false;
  }
  Vertex vertex;
  toFrame(frame, p, vertex.xyz);
  vertex.tet = kNoTet;
  vertex.point = id;
  return triangulator->insertOne(vertex, change.deleted, change.made);
}

Triangulation IncrementalDelaunay::Impl::output(bool release, Coordinates* xyz)
{
  if (released)
    throw std::logic_error("fd3::IncrementalDelaunay: the mesh was released");
  const auto start = Clock::now();
  if (xyz)
    giveBackPoints(*xyz);
  Triangulation out;
  out.status = status;
  out.stats = stats;
  if (status != Status::Ok)
    return out;
  out.stats.add(triangulator->statistics()); // the inserters' figures: none of them are in stats
  triangulator->addPredicateCounts(out.stats);
  const auto repeated = triangulator->duplicates();
  out.stats.duplicatesMerged += repeated.size();
#ifndef NDEBUG
  constexpr bool kDebugBuild = true;
#else
  constexpr bool kDebugBuild = false;
#endif
  if (options.checkMesh || kDebugBuild)
  {
    out.checkReport = triangulator->checkMesh();
    if (!out.checkReport.empty())
    {
      out.status = Status::CheckFailed;
      return out;
    }
  }
  const std::size_t slots = triangulator->slots();
  const std::size_t vertexCount = triangulator->vertices().size();
  const std::vector<VertId> hiddenVertices = triangulator->hidden(); // the inserters' lists
  IdArray records;
  std::vector<std::uint32_t> copiedIds; // the mesh goes on: its vertices stay
  const std::uint32_t* pointOf = nullptr;
  if (release)
  {
    records = triangulator->releaseWorkspace().takeRecords();
    pointOf = triangulator->packPointIds();
  }
  else
  {
    records = triangulator->copyRecords();
    for (const Vertex& vertex : triangulator->vertices())
      copiedIds.push_back(vertex.point);
    pointOf = copiedIds.data();
  }
  extractOutput(std::move(records), slots, pointOf, options.computeNeighbors, out, *team);
  out.representative.resize(points);
  team->forRanges(points, "output", [&](std::size_t, std::size_t begin, std::size_t end) {
    std::fill(out.representative.begin() + static_cast<std::ptrdiff_t>(begin),
      out.representative.begin() + static_cast<std::ptrdiff_t>(end), kNoPoint);
  });
  team->forRanges(vertexCount, "output", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
      out.representative[pointOf[v]] = pointOf[v];
  });
  for (const auto& [point, near] : skipped)
    out.representative[point] = near;
  for (const auto& [copy, original] : repeated)
    out.representative[pointOf[copy]] = pointOf[original];
  for (const auto& [copy, original] : duplicates)
    out.representative[copy] = out.representative[original];
  if (weighted)
  {
    out.hidden = hiddenCopies;
    for (const VertId v : hiddenVertices)
      out.hidden.push_back(pointOf[v]);
    std::sort(out.hidden.begin(), out.hidden.end());
    for (const std::uint32_t id : hiddenCopies)
      out.representative[id] = id;
  }
  if (release)
  {
    triangulator->releasePages();
    triangulator.reset();
    released = true;
  }
  out.stats.tetrahedra = out.numberOfTetrahedra();
  out.stats.secondsOutput = secondsSince(start);
  out.threadedWork = team->records();
  return out;
}

const double* IncrementalDelaunay::Impl::heldPoint(std::size_t id) const
{
  return id >= heldFrom && id - heldFrom < held.size() / 3 ? &held[3 * (id - heldFrom)] : nullptr;
}

std::vector<VertId> IncrementalDelaunay::Impl::vertexOfPoint() const
{
  std::vector<VertId> vertexOf(points, kNoVertex);
  if (triangulator)
  {
    const VertexArray& vertices = triangulator->vertices();
    for (VertId v = 0; v < vertices.size(); ++v)
      vertexOf[vertices[v].point] = v;
  }
  return vertexOf;
}

void IncrementalDelaunay::Impl::freeRecoverablePoints()
{
  const std::size_t count = held.size() / 3;
  if (heldFrom != 0 || options.tolerance != 0 || !recoverable(frame, held.data(), count))
    return; // a point skipped for the tolerance has no record
  for (std::size_t i = 0; i < count; ++i)
    if (!isFinite(&held[3 * i]))
      aside.push_back(
        {static_cast<std::uint32_t>(i), {held[3 * i], held[3 * i + 1], held[3 * i + 2]}});
  heldFrom = count;
  Coordinates().swap(held);
}

void IncrementalDelaunay::Impl::giveBackPoints(Coordinates& xyz)
{
  if (heldFrom == 0)
  {
    xyz = std::move(held);
    return;
  }
  // Every point is written: the first batch's finite points are vertices or exact duplicates
  // (no tolerance), its others are aside, and the later batches are held.
  xyz.resize(3 * points);
  writeRecordedPoints(xyz.data());
  for (const auto& [id, p] : aside)
    std::copy(p.begin(), p.end(), xyz.begin() + 3 * std::size_t(id));
  std::copy(held.begin(), held.end(), xyz.begin() + 3 * heldFrom);
  Coordinates().swap(held);
}

void IncrementalDelaunay::Impl::writeRecordedPoints(double* xyz) const
{
  const VertexArray& vertices = triangulator->vertices();
  std::vector<bool> written(points, false);
  for (const Vertex& vertex : vertices) // repeated vertices (duplicates() of add()) included
  {
    for (int a = 0; a < 3; ++a)
      xyz[3 * std::size_t(vertex.point) + a] = fromFrame(frame, vertex.xyz[a], a);
    written[vertex.point] = true;
  }
  for (const auto& [copy, original] : duplicates) // an original skipped for the tolerance is not
    if (written[original])
      std::copy_n(xyz + 3 * std::size_t(original), 3, xyz + 3 * std::size_t(copy));
}

void IncrementalDelaunay::Impl::takeOptions(const Options& givenOptions, const double* givenWeights)
{
  options = givenOptions;
  weights = givenWeights;
  if (weights)
    options.volumeThreshold = 0; // the regular tetrahedralization, exactly
}

void IncrementalDelaunay::Impl::start(const double* xyz, std::size_t count,
  const Options& givenOptions, const Frame& givenFrame, std::size_t givenRoom,
  const double* givenWeights)
{
  takeOptions(givenOptions, givenWeights);
  frame = givenFrame;
  room = givenRoom;
  insertFirst(xyz, count);
  if (!triangulator) // until the mesh can start
  {
    if (!takesPoints)
      held.assign(xyz, xyz + 3 * count);
    if (weights)
      heldWeights.assign(weights, weights + count);
  }
}

IncrementalDelaunay::IncrementalDelaunay(const double* xyz, std::size_t count,
  const Options& options, const Frame& frame, std::size_t room, const double* weights)
  : impl_(std::make_unique<Impl>())
{
  impl_->start(xyz, count, options, frame, room, weights);
}

IncrementalDelaunay::IncrementalDelaunay(
  const double* xyz, const double* weights, std::size_t count, const Options& options)
  : impl_(std::make_unique<Impl>())
{
  impl_->takeOptions(options, weights);
  impl_->frameGiven = false;
  impl_->insertFirst(xyz, count);
}

IncrementalDelaunay::IncrementalDelaunay(Coordinates xyz, const Options& options,
  const Frame& frame, std::size_t room, const double* weights)
  : impl_(std::make_unique<Impl>())
{
  if (xyz.size() % 3 != 0)
    throw std::invalid_argument("fd3::IncrementalDelaunay: coordinates are not in threes");
  impl_->takesPoints = true;
  impl_->held = std::move(xyz);
  impl_->start(impl_->held.data(), impl_->held.size() / 3, options, frame, room, weights);
}

IncrementalDelaunay::IncrementalDelaunay() : impl_(std::make_unique<Impl>()) {}

std::unique_ptr<IncrementalDelaunay> IncrementalDelaunay::ofImages(Coordinates xyz,
  const ImageOf* images, const Options& options, const Frame& frame, const double* weights)
{
  std::unique_ptr<IncrementalDelaunay> mesh(new IncrementalDelaunay());
  Impl& impl = *mesh->impl_;
  impl.images = images;
  impl.takesPoints = true;
  impl.held = std::move(xyz);
  impl.start(impl.held.data(), impl.held.size() / 3, options, frame, 0, weights);
  impl.images = nullptr; // the caller's, read during the call only
  return mesh;
}

std::size_t IncrementalDelaunay::mergedPoints() const
{
  return impl_->stats.duplicatesMerged +
    (impl_->triangulator ? impl_->triangulator->duplicates().size() : 0);
}

void IncrementalDelaunay::addImages(
  const double* xyz, const ImageOf* images, std::size_t count, const double* weights)
{
  if (!impl_->triangulator)
    throw std::logic_error("fd3::IncrementalDelaunay::addImages: the mesh has not started");
  impl_->images = images;
  add(xyz, count, weights);
  impl_->images = nullptr;
}

void IncrementalDelaunay::visitTetrahedra(const std::function<void(
    const std::uint32_t ids[4], const double* const xyz[4], const double* weights)>& visit) const
{
  if (impl_->released || !impl_->triangulator)
    return;
  const TetMesh& mesh = impl_->triangulator->tetrahedra();
  const VertexArray& vertices = impl_->triangulator->vertices();
  const std::vector<double>& weightOf = impl_->triangulator->weights();
  impl_->team->forRanges(
    mesh.slots(), "visit", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
      {
        // The slots run in no order of the vertices: their records are fetched ahead.
        if (t + kFetchAhead < end && !mesh.isDead(TetId(t + kFetchAhead)))
          for (int i = 0; i < 4; ++i)
            if (const VertId v = mesh.vertex(TetId(t + kFetchAhead), i); v != kInfinite)
              prefetch(&vertices[v]);
        if (mesh.isDead(TetId(t)) || mesh.isGhost(TetId(t)))
          continue;
        static constexpr int kAll[4] = {0, 1, 2, 3};
        std::uint32_t ids[4];
        const double* xyz[4];
        vertexRecords(mesh, vertices, TetId(t), kAll, 4, ids, xyz);
        double weights[4];
        if (!weightOf.empty())
          for (int i = 0; i < 4; ++i)
            weights[i] = weightOf[mesh.vertex(TetId(t), i)];
        visit(ids, xyz, weightOf.empty() ? nullptr : weights);
      }
    });
}

void IncrementalDelaunay::visitHullFaces(
  const std::function<void(const std::uint32_t ids[3], const double* const xyz[3])>& visit) const
{
  if (impl_->released || !impl_->triangulator)
    return;
  const TetMesh& mesh = impl_->triangulator->tetrahedra();
  const VertexArray& vertices = impl_->triangulator->vertices();
  impl_->team->forRanges(
    mesh.slots(), "visit", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t g = begin; g < end; ++g)
      {
        if (mesh.isDead(TetId(g)) || !mesh.isGhost(TetId(g)))
          continue;
        // A ghost's finite face is the one opposite its vertex at infinity, 3.
        const FaceCode across = mesh.neighbor(TetId(g), 3);
        std::uint32_t ids[3];
        const double* xyz[3];
        vertexRecords(mesh, vertices, tetOf(across), kFaceVertices[faceOf(across)], 3, ids, xyz);
        visit(ids, xyz);
      }
    });
}

IncrementalDelaunay::~IncrementalDelaunay() = default;

Status IncrementalDelaunay::status() const
{
  return impl_->status;
}

std::size_t IncrementalDelaunay::pointCount() const
{
  return impl_->points;
}

void IncrementalDelaunay::add(const double* xyz, std::size_t count, const double* weights)
{
  if (impl_->released || impl_->status == Status::Aborted || impl_->status == Status::CheckFailed)
    throw std::logic_error("fd3::IncrementalDelaunay::add: the tetrahedralization ended");
  impl_->insertMore(xyz, count, weights);
}

bool IncrementalDelaunay::addOne(const double p[3], MeshChange& change)
{
  if (impl_->released || impl_->status != Status::Ok)
    throw std::logic_error("fd3::IncrementalDelaunay::addOne: no tetrahedralization to add to");
  if (impl_->weighted)
    throw std::logic_error("fd3::IncrementalDelaunay::addOne: a weighted mesh takes add() only");
  if (impl_->points + 1 >= kMaxVertices)
    throw std::length_error("fd3::IncrementalDelaunay::addOne: more than 2^30 points");
  return impl_->insertOne(p, change);
}

std::vector<std::uint32_t> IncrementalDelaunay::liveTetrahedra() const
{
  std::vector<std::uint32_t> live;
  if (impl_->released || !impl_->triangulator)
    return live;
  const TetMesh& mesh = impl_->triangulator->tetrahedra();
  for (TetId t = 0; t < mesh.slots(); ++t)
    if (!mesh.isDead(t) && !mesh.isGhost(t))
      live.push_back(t);
  return live;
}

void IncrementalDelaunay::tetrahedron(std::uint32_t t, std::uint32_t ids[4]) const
{
  const TetMesh& mesh = impl_->triangulator->tetrahedra();
  const VertexArray& vertices = impl_->triangulator->vertices();
  for (int k = 0; k < 4; ++k)
    ids[k] = vertices[mesh.vertex(t, k)].point;
}

Triangulation IncrementalDelaunay::snapshot() const
{
  return impl_->output(false);
}

Triangulation IncrementalDelaunay::release()
{
  return impl_->output(true);
}

Triangulation IncrementalDelaunay::release(Coordinates& xyz)
{
  if (!impl_->takesPoints)
    throw std::logic_error("fd3::IncrementalDelaunay::release: the mesh did not take its points");
  return impl_->output(true, &xyz);
}

std::vector<std::vector<double>> IncrementalDelaunay::points(
  const std::vector<std::vector<std::uint32_t>>& lists) const
{
  std::vector<std::vector<double>> out(lists.size());
  std::vector<VertId> vertexOf; // made for the first point that the mesh does not hold
  for (std::size_t l = 0; l < lists.size(); ++l)
  {
    out[l].resize(3 * lists[l].size());
    for (std::size_t k = 0; k < lists[l].size(); ++k)
    {
      const std::uint32_t id = lists[l][k];
      if (const double* p = impl_->heldPoint(id))
      {
        std::copy_n(p, 3, &out[l][3 * k]);
        continue;
      }
      if (vertexOf.empty())
        vertexOf = impl_->vertexOfPoint();
      if (id >= vertexOf.size() || vertexOf[id] == kNoVertex)
        throw std::invalid_argument("fd3::IncrementalDelaunay::points: not a vertex");
      const Vertex& vertex = impl_->triangulator->vertices()[vertexOf[id]];
      for (int a = 0; a < 3; ++a)
        out[l][3 * k + a] = fromFrame(impl_->frame, vertex.xyz[a], a);
    }
  }
  return out;
}

std::size_t IncrementalDelaunay::heldPoints() const
{
  return impl_->held.size() / 3;
}

std::vector<std::vector<std::uint32_t>> IncrementalDelaunay::haloVertices(
  const std::vector<Bounds>& boxes, double heaviest) const
{
  // In the frame, from the vertex records: they lie in insertion order, as the tetrahedra that
  // use them were made, where the input's coordinates lie in input order and a pass over the
  // tetrahedra would miss the cache at almost every vertex. The frame is monotone on each axis, so
  // a point within a box is within the box's image.
  std::vector<Bounds> framed = boxes;
  for (Bounds& box : framed)
    box = toFrame(impl_->frame, box);
  const bool weighted = impl_->weighted;
  if (weighted)
    heaviest = std::ldexp(heaviest, impl_->frame.identity ? 0 : 2 * std::ilogb(impl_->frame.scale));
  HaloBuilder halo(framed, heaviest);
  if (impl_->status != Status::Ok || !impl_->triangulator)
    return halo.take();
  const TetMesh& mesh = impl_->triangulator->tetrahedra();
  const VertexArray& vertices = impl_->triangulator->vertices();
  auto pointOf = [&](VertId v) { return vertices[v].point; };
  auto point = [&](VertId v) { return vertices[v].xyz; };
  for (TetId t = 0; t < impl_->triangulator->slots(); ++t)
  {
    if (mesh.isDead(t))
      continue;
    VertId v[4];
    mesh.vertices(t, v);
    if (v[3] == kInfinite) // the hull face v0 v1 v2; the finite tetrahedron behind it is inside
    {
      const FaceCode behind = mesh.neighbor(t, 3);
      const std::uint32_t ids[3] = {pointOf(v[0]), pointOf(v[1]), pointOf(v[2])};
      const double* p[3] = {point(v[0]), point(v[1]), point(v[2])};
      halo.hullFace(p, point(mesh.vertex(tetOf(behind), faceOf(behind))), ids);
    }
    else
    {
      const std::uint32_t ids[4] = {pointOf(v[0]), pointOf(v[1]), pointOf(v[2]), pointOf(v[3])};
      const double* p[4] = {point(v[0]), point(v[1]), point(v[2]), point(v[3])};
      if (weighted)
      {
        const std::vector<double>& w = impl_->triangulator->weights();
        const double tw[4] = {w[v[0]], w[v[1]], w[v[2]], w[v[3]]};
        halo.tetrahedron(p, ids, tw);
      }
      else
        halo.tetrahedron(p, ids);
    }
  }
  return halo.take();
}

Triangulation triangulate(const double* xyz, std::size_t count, const Options& options)
{
  return triangulate(xyz, nullptr, count, options);
}

Triangulation triangulate(
  const double* xyz, const double* weights, std::size_t count, const Options& options)
{
  const auto start = Clock::now();
  IncrementalDelaunay mesh(xyz, weights, count, options);
  Triangulation out = mesh.release();
  out.stats.secondsTotal = secondsSince(start);
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
    case Status::OutOfRange:
      return "the points and box span more than doubles hold (Voronoi vertices, or images of "
             "points far from a periodic box), or a weight exceeds most by more than (4 periods)^2";
  }
  return "unknown";
}

} // namespace fd3
