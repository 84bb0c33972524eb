#include "insertion/Inserter.h"

#include <chrono>
#include <utility>

namespace fd3
{

Inserter::Inserter(Mesh& mesh, SlotPool& pool, const Predicates& predicates, std::uint64_t seed)
  : mesh_(mesh), tets_(mesh.tets), pool_(pool), predicates_(predicates),
    rng_(seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)
{}

std::uint32_t Inserter::nextRandom()
{
  // xorshift64*: cheap, seeded, and good enough to break the walk's symmetries.
  rng_ ^= rng_ >> 12;
  rng_ ^= rng_ << 25;
  rng_ ^= rng_ >> 27;
  return static_cast<std::uint32_t>((rng_ * 0x2545F4914F6CDD1Dull) >> 32);
}

// The first tetrahedron and the four ghosts that close its hull.
void Inserter::start()
{
  VertId v[4] = {0, 1, 2, 3};
  if (predicates_.orient3d(point(0), point(1), point(2), point(3)) < 0)
    std::swap(v[0], v[1]);
  TetId slot[5];
  tets_.makeRoom(5);
  pool_.take(tets_, 5, slot);
  const TetId t = slot[0];
  tets_.create(t, v);
  // Ghost i sits on the face opposite v[i], in its outward order: the face normal then points away
  // from v[i], out of the hull.
  const TetId* ghost = slot + 1;
  for (int i = 0; i < 4; ++i)
  {
    const int* f = kFaceVertices[i];
    const VertId face[4] = {v[f[0]], v[f[1]], v[f[2]], kInfinite};
    tets_.create(ghost[i], face);
    tets_.link(faceCode(t, i), faceCode(ghost[i], 3));
  }
  // Ghosts meet along the edges of t: ghost i's face opposite its vertex k is the edge of
  // ghost i's hull face without that vertex, shared with the ghost on the other side of that edge.
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
    {
      const VertId missing = tets_.vertex(ghost[i], k);
      int j = 0;
      while (v[j] != missing)
        ++j;
      // The other ghost holding the edge is the one opposite `missing`; in it, the face opposite
      // v[i] is the one on the edge.
      int kk = 0;
      while (tets_.vertex(ghost[j], kk) != v[i])
        ++kk;
      tets_.setNeighbor(faceCode(ghost[i], k), faceCode(ghost[j], kk));
    }
  for (int i = 0; i < 4; ++i)
  {
    mesh_.vertices[v[i]].tet = t;
    if (mesh_.grid.enabled())
      mesh_.grid.markInserted(mesh_.grid.cellOf(point(v[i])), v[i]);
  }
  lastInserted_ = 3;
  regionStart_ = t;
  stats_.insertedPoints = 4;
}

void Inserter::restrictTo(const Region& region, TetId start)
{
  region_ = region;
  restricted_ = true;
  regionStart_ = start;
}

void Inserter::unrestricted()
{
  restricted_ = false;
}

void Inserter::lockIn(OwnerTable* owners, std::size_t slots, std::uint8_t me)
{
  owners_ = owners;
  ownerSlots_ = slots;
  me_ = me;
  restricted_ = false;
}

void Inserter::unlocked()
{
  owners_ = nullptr;
  ownerSlots_ = 0;
}

bool Inserter::acquire(TetId t)
{
  if (t >= ownerSlots_)
    return false; // a vertex's tetrahedron read while its first one was being made
  std::uint8_t holder = owners_[t].load(std::memory_order_relaxed);
  if (holder == me_)
    return true;
  if (holder != 0 ||
    !owners_[t].compare_exchange_strong(
      holder, me_, std::memory_order_acquire, std::memory_order_relaxed))
    return false;
  held_.push_back(t);
  return true;
}

bool Inserter::mayEnterShared(TetId t, int entryFace)
{
  // t shares with the one the walk leaves, the inserter's, all vertices but the one opposite.
  if (!owners_)
    return entryFace < 0 ? isOwned(t) : inRegion(tets_.vertex(t, entryFace));
  const std::size_t before = held_.size();
  if (!acquire(t))
    return false;
  const bool taken = held_.size() > before;
  if (tets_.isDead(t)) // a start read from a vertex whose tetrahedra changed since
  {
    if (taken)
    {
      owners_[t].store(0, std::memory_order_release);
      held_.pop_back();
    }
    return false;
  }
  // Hand over hand: the walk holds only the tetrahedron it is in. While it holds one, no other
  // inserter can delete a neighbour of it (that would relink the held one), so the next is live.
  if (taken && before > 0)
  {
    owners_[held_[before - 1]].store(0, std::memory_order_release);
    held_[before - 1] = t;
    held_.pop_back();
  }
  return true;
}

void Inserter::releaseHeld()
{
  for (const TetId t : held_)
    if (!tets_.isDead(t))
      owners_[t].store(0, std::memory_order_release);
  held_.clear();
}

bool Inserter::mayTouch(TetId t) const
{
  if (owners_)
    return isOwned(t);
  if (!restricted_)
    return true;
  VertId tv[4];
  tets_.vertices(t, tv);
  return inRegion(tv[0]) + inRegion(tv[1]) + inRegion(tv[2]) + inRegion(tv[3]) >= 3;
}

bool Inserter::allVerticesInRegion(TetId t) const
{
  VertId tv[4];
  tets_.vertices(t, tv);
  return inRegion(tv[0]) && inRegion(tv[1]) && inRegion(tv[2]) && inRegion(tv[3]);
}

namespace
{
// Phase times are measured on one insertion in kSampling and scaled up: reading the clock around
// every phase of every insertion would cost more than the shortest phases.
constexpr VertId kSampling = 16;

class PhaseClock
{
public:
  explicit PhaseClock(bool on) : on_(on)
  {
    if (on_)
      last_ = std::chrono::steady_clock::now();
  }
  void lap(double& seconds)
  {
    if (!on_)
      return;
    const auto now = std::chrono::steady_clock::now();
    seconds += kSampling * std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

private:
  bool on_;
  std::chrono::steady_clock::time_point last_;
};
} // namespace

Inserter::Outcome Inserter::deferred()
{
  lockLost_ = false;
  if (owners_)
    releaseHeld();
  ++stats_.deferredInsertions;
  return Outcome::Deferred;
}

template <Inserter::Access A>
Inserter::Outcome Inserter::insertAs(VertId v)
{
  PhaseClock clock(v % kSampling == 0);
  const BackgroundGrid::Cell cell = gridCell(v); // for the search and the mark after
  const TetId base = locate(v, cell);
  clock.lap(stats_.secondsLocate);
  if (lookForDuplicates_ && base != kNoTet)
    if (const VertId repeated = repeatedVertex(base, v);
        repeated != kNoVertex && (!mesh_.weighted() || mesh_.weights[repeated] == mesh_.weights[v]))
    {
      duplicates_.emplace_back(v, repeated);
      if (owners_)
        releaseHeld();
      return Outcome::Duplicate;
    }
  if (mesh_.weighted() && base != kNoTet && !baseInConflict(base, v))
  {
    hide(v);
    if (owners_)
      releaseHeld();
    return Outcome::Hidden;
  }
  if (base == kNoTet || !digCavity<A>(base, v))
  {
    // The base is unchanged and near the next point: the last tetrahedron created may lie many
    // put-off points back, where most insertions reach outside their region.
    if (base != kNoTet)
      regionStart_ = base;
    return deferred();
  }
  correctCavity(v);
  if (mesh_.weighted())
    collectCavityVertices();
  clock.lap(stats_.secondsCavity);
  if (!fillCavity<A>(v))
    return deferred();
  if (mesh_.weighted())
    hideEnclosedVertices();
  clock.lap(stats_.secondsFill);
  // Past about one test in nine that the static filter leaves to the lifts' filter (a cavity and
  // its boundary hold about 2.2 tests per deleted tetrahedron), its mispredicted branch costs more
  // than the lifts' filter on every test.
  if (!predicates_.prefersLiftsFilter() &&
    predicates_.liftsFilterRescues() > stats_.cavityTetrahedra / 4 + 4096)
    predicates_.preferLiftsFilter();
  if constexpr (A == Access::Locking)
    releaseHeld();
  if (mesh_.grid.enabled())
    mesh_.grid.markInserted(cell, v);
  lastInserted_ = v;
  ++stats_.insertedPoints;
  return Outcome::Inserted;
}

template Inserter::Outcome Inserter::insertAs<Inserter::Access::Free>(VertId);
template Inserter::Outcome Inserter::insertAs<Inserter::Access::Region>(VertId);
template Inserter::Outcome Inserter::insertAs<Inserter::Access::Locking>(VertId);

} // namespace fd3
