#include "insertion/Triangulator.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numeric>
#include <utility>

namespace fd3
{
Triangulator::Triangulator(VertexArray vertices, const Bounds& box, const Options& options,
  ThreadTeam& team, bool anyMagnitude, std::vector<double> weights)
  : team_(team), tuning_(options.randomSeed), staticBox_(box)
{
  mesh_.vertices = std::move(vertices);
  mesh_.weights = std::move(weights);
  mesh_.options = options;
  const std::size_t n = vertexCount();
  mesh_.tets.reserve(7 * n + 64); // uniform points make 6.7 per vertex; insertAll() corrects it
  mesh_.grid.build(n, box, options.pointsPerCell, team.stretches("grid"));
  tuning_.adaptTo(mesh_.vertices[0].xyz, n, sizeof(Vertex) / sizeof(double), box);
  if (anyMagnitude)
    tuning_.allowAnyMagnitude();
  if (mesh_.weighted())
    adaptToWeights();
  for (int t = 0; t < team.size(); ++t)
  {
    pools_.push_back(std::make_unique<SlotPool>());
    inserters_.push_back(std::make_unique<Inserter>(
      mesh_, *pools_.back(), tuning_, options.randomSeed + static_cast<std::uint64_t>(t)));
  }
}

bool Triangulator::insertAll(
  const std::vector<std::size_t>& roundStarts, const std::function<bool(double)>& progress)
{
  inserters_[0]->start();
  done_ = 4;
  return insertRounds(4, vertexCount(), roundStarts, true, progress);
}

void Triangulator::useImages(std::vector<ImageOf> images)
{
  images_.assign(std::move(images));
  images_.locate(mesh_.vertices[0].xyz, sizeof(Vertex) / sizeof(double));
  tuning_.useImages(&images_);
  if (mesh_.weighted()) // the power test's static bound widens with the images' slack
    adaptToWeights();
  for (auto& inserter : inserters_)
    inserter->retune(tuning_);
}

bool Triangulator::insertMore(VertexArray more, std::vector<double> weights,
  const std::vector<std::size_t>& roundStarts, const std::function<bool(double)>& progress,
  const std::vector<ImageOf>& images)
{
  const std::size_t begin = vertexCount();
  tuneFor(more.data(), more.size());
  if (mesh_.weighted())
  {
    mesh_.weights.insert(mesh_.weights.end(), weights.begin(), weights.end());
    adaptToWeights();
  }
  for (auto& inserter : inserters_)
  {
    inserter->retune(tuning_);
    inserter->lookForDuplicates();
  }
  mesh_.vertices.insert(mesh_.vertices.end(), more.begin(), more.end());
  if (images_.size() > 0)
  {
    images_.append(images);
    images_.locate(mesh_.vertices[0].xyz, sizeof(Vertex) / sizeof(double)); // they may have moved
  }
  std::vector<std::size_t> starts(roundStarts);
  for (std::size_t& start : starts)
    start += begin;
  makeRoomFor(more.size());
  return insertRounds(begin, vertexCount(), starts, false, progress);
}

bool Triangulator::insertOne(
  const Vertex& vertex, std::vector<TetId>& deleted, std::vector<TetId>& made)
{
  tuneFor(&vertex, 1);
  Inserter& inserter = *inserters_[0];
  inserter.retune(tuning_);
  inserter.lookForDuplicates();
  inserter.unrestricted();
  mesh_.vertices.push_back(vertex);
  makeRoomFor(1);
  const VertId v = static_cast<VertId>(vertexCount() - 1);
  Inserter::Outcome outcome;
  while ((outcome = inserter.insert(v)) == Inserter::Outcome::Deferred)
    growRecords();
  ++done_;
  pools_[0]->retire(mesh_.tets); // every slot below slots() live or dead, as after a round
  if (outcome == Inserter::Outcome::Duplicate)
    return false;
  // Hidden would leave the last cavity's lists the previous insertion's: IncrementalDelaunay::
  // addOne() refuses weighted meshes, where alone a point can be hidden.
  assert(outcome == Inserter::Outcome::Inserted);
  const TetMesh& tets = mesh_.tets;
  for (const FaceCode c : inserter.lastCavity().deleted)
    if (!tets.isGhost(tetOf(c)))
      deleted.push_back(tetOf(c));
  for (const TetId t : inserter.lastCavity().created)
    if (!tets.isGhost(t))
      made.push_back(t);
  return true;
}

bool Triangulator::insertRounds(std::size_t begin, std::size_t end,
  const std::vector<std::size_t>& roundStarts, bool reserveEarly,
  const std::function<bool(double)>& progress)
{
  const bool parallel = inserters_.size() > 1 && mesh_.options.volumeThreshold <= 0;
  // Once a few rounds are in (random samples of the whole set), the tetrahedra per vertex tell
  // the final count, and memory for all is reserved (only what is written becomes resident).
  const std::size_t reserveAt = std::max<std::size_t>(end / 32, 4096);
  bool reserved = !reserveEarly;
  for (std::size_t r = 0; r < roundStarts.size(); ++r)
  {
    const std::size_t first = std::max(roundStarts[r], begin);
    const std::size_t last = std::min(r + 1 < roundStarts.size() ? roundStarts[r + 1] : end, end);
    if (first >= last)
      continue;
    // Parallel passes pay for their threads: rounds too small for two go in serially.
    bool ok = false;
    if (parallel && last - first >= 2 * kMinPointsPerThread)
    {
      IdArray round(last - first);
      team_.forRanges(
        round.size(), "regions", [&](std::size_t, std::size_t begin, std::size_t end) {
          std::iota(round.begin() + std::ptrdiff_t(begin), round.begin() + std::ptrdiff_t(end),
            static_cast<VertId>(first + begin));
        });
      ok = insertInParallel(std::move(round), progress);
    }
    else
    {
      auto rank = [first](std::size_t i) { return static_cast<VertId>(first + i); };
      ok = insertSerially(last - first, rank, progress);
    }
    if (!ok)
      return false;
    if (!reserved && done_ >= reserveAt)
    {
      mesh_.tets.reserve(predictedSlots(end, kReserveMargin), team_.stretches("records"));
      reserved = true;
    }
    earlierDone_ = done_;
    earlierSlots_ = mesh_.tets.slots();
  }
  for (auto& pool : pools_)
    pool->retire(mesh_.tets);
  return true;
}

std::size_t Triangulator::predictedSlots(std::size_t vertices, double margin) const
{
  const double perVertex = double(mesh_.tets.slots()) / double(std::max<std::size_t>(done_, 1));
  // Smooth surface samples gain tetrahedra per vertex at a steady rate per doubling of the points:
  // a reserve at the ratio of the moment runs out in the last round, and growing the records then
  // holds two copies at once. Volume data gains none, or fewer ghosts per vertex, which only the
  // margin takes.
  double growth = 0.0;
  if (earlierDone_ > 0 && done_ > earlierDone_)
    growth = std::max(0.0,
      (perVertex - double(earlierSlots_) / double(earlierDone_)) /
        std::log2(double(done_) / double(earlierDone_)));
  const double expected = std::min(
    perVertex + growth * std::log2(double(vertices) / double(std::max<std::size_t>(done_, 1))),
    2.0 * perVertex);
  return static_cast<std::size_t>(margin * expected * double(vertices)) + 64;
}

void Triangulator::makeRoomFor(std::size_t count)
{
  // The slots the vertices so far and `count` more are expected to take (their high-water mark),
  // with a margin on what they add, and a block's worth for every pool. A margin on the whole
  // would outgrow the reserve in the late passes, whose ratio is measured over more vertices, and
  // copy the records for room no pass uses.
  const std::size_t expected = predictedSlots(done_ + count, 1.0);
  const std::size_t slots = mesh_.tets.slots();
  const double added = expected > slots ? double(expected - slots) : 0.0;
  mesh_.tets.makeRoom(
    static_cast<std::size_t>(kPassMargin * added) + 2 * SlotPool::kBlock * pools_.size() + 1024,
    team_.stretches("records"));
}

void Triangulator::growRecords()
{
  // A cavity larger than the room left: at least a quarter more, whatever the prediction says.
  mesh_.tets.makeRoom(mesh_.tets.capacity() - mesh_.tets.slots() + 1, team_.stretches("records"));
}

bool Triangulator::reportProgress(const std::function<bool(double)>& progress)
{
  if (progress && !stop_ && !progress(double(done_ + passDone_) / double(vertexCount())))
    stop_ = true;
  return !stop_;
}

Statistics Triangulator::statistics() const
{
  Statistics sum;
  for (const auto& inserter : inserters_)
    sum.add(inserter->stats());
  return sum;
}

std::vector<std::pair<VertId, VertId>> Triangulator::duplicates() const
{
  std::vector<std::pair<VertId, VertId>> all;
  for (const auto& inserter : inserters_)
    all.insert(all.end(), inserter->duplicates().begin(), inserter->duplicates().end());
  return all;
}

void Triangulator::tuneFor(const Vertex* more, std::size_t count)
{
  tuning_.include(more[0].xyz, count, sizeof(Vertex) / sizeof(double));
  Bounds box = staticBox_;
  for (std::size_t i = 0; i < count; ++i)
    box.include(more[i].xyz);
  if (!(box == staticBox_))
  {
    staticBox_ = box;
    tuning_.widenTo(staticBox_);
  }
}

void Triangulator::adaptToWeights()
{
  const auto [lowest, highest] = std::minmax_element(mesh_.weights.begin(), mesh_.weights.end());
  tuning_.adaptToWeights(*lowest, *highest);
}

std::vector<VertId> Triangulator::hidden() const
{
  std::vector<VertId> all;
  for (const auto& inserter : inserters_)
    all.insert(all.end(), inserter->hidden().begin(), inserter->hidden().end());
  return all;
}

void Triangulator::addPredicateCounts(Statistics& stats) const
{
  for (const auto& inserter : inserters_)
  {
    const Predicates& p = inserter->predicates();
    stats.exactOrient += p.exactOrientCalls;
    stats.exactInSphere += p.exactInSphereCalls;
    stats.symbolicTies += p.symbolicTies;
    stats.integerExact += p.integerExactCalls;
  }
}

TetMesh& Triangulator::releaseWorkspace()
{
  inserters_.clear();
  pools_.clear();
  mesh_.grid = BackgroundGrid();
  return mesh_.tets;
}

void Triangulator::releasePages()
{
  team_.release(mesh_.vertices, "output");
  if (owners_)
    team_.releasePages(owners_.get(), ownerSlots_ * sizeof(OwnerTable), "output");
}

const std::uint32_t* Triangulator::packPointIds()
{
  // Id i goes to bytes 4i..4i+3, inside vertex record i/8: the ids of vertices [a, 2a) go into
  // records below a/4, which have been read, so each such range is packed on every thread at once,
  // one after another (vertex 0's id is read before its first coordinate is overwritten).
  unsigned char* packed = reinterpret_cast<unsigned char*>(mesh_.vertices.data());
  const std::size_t n = mesh_.vertices.size();
  ThreadedWork& record = team_.newRecord("output");
  for (std::size_t a = 0, b = 1; a < n; a = b, b = 2 * b)
  {
    const std::size_t end = std::min(b, n), parts = team_.partsFor(end - a);
    team_.run(
      parts,
      [&](std::size_t k) {
        const Part part = partOf(end - a, k, parts);
        const std::size_t first = a + part.first, last = a + part.last;
        const Vertex* vertices = mesh_.vertices.data();
        for (std::size_t i = first; i < last; ++i)
        {
          const std::uint32_t point = vertices[i].point;
          std::memcpy(packed + sizeof(point) * i, &point, sizeof(point));
        }
      },
      record);
  }
  return reinterpret_cast<const std::uint32_t*>(packed);
}

} // namespace fd3
