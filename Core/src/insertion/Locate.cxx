// Finding where the new point goes: a tetrahedron in conflict with it, from which the cavity is
// grown. The paper walks to the base, the tetrahedron that contains the point, because an inexact
// insphere test could make a cavity grown from elsewhere disconnected. Our predicates are exact, so
// on a Delaunay mesh the conflict zone is connected and contains the base: the walk stops at the
// first tetrahedron that it meets in conflict, as far as the first float filter of insphere tells
// (near-ties are left to the walk: the base is in conflict anyway). On surface samples, where thin
// tetrahedra fan out around every vertex, that is most often the start itself, which shortens
// the walks there several times. A volume threshold leaves the mesh short of Delaunay, so the
// walk then goes on to the base, which the core correction needs. On weighted points the conflict
// zone, where there is one, is connected and contains the base too, so the walk stops as early;
// where there is none, it ends at the base, which tells that the point is hidden.
#include "insertion/Inserter.h"

#include "fd3/Measures.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace fd3
{
namespace
{
// Layers of the onion searched before giving up on the grid (early BRIO rounds, where the points
// inserted so far are far apart).
constexpr int kMaxOnionLayers = 3;
// Steps after which the walk draws its first face at random: a safety net against cycles, which
// the distance order cannot have on a Delaunay mesh but might on one built with a volume threshold.
constexpr std::size_t kOrderedSteps = 1000;
// Steps after which the walk gives up and scans the mesh instead (scanForBase()): far beyond any
// walk of a valid mesh, a bound on the walk whatever happens.
constexpr std::size_t kMaxSteps = 100000;
// The most steps a walk may take over the hull, from ghost to ghost, before it goes inside.
constexpr int kHullSteps = 8;

void cross(const double* u, const double* v, double* out)
{
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}

double dot(const double* u, const double* v)
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

// orderByDistance()'s keys: for each vertex q[k], the bits of distance2(q[k], p) with the lowest
// two replaced by k. With AVX, in four lanes: the same operations in the same order, so the same
// doubles.
void distanceKeys(const double* const q[4], const double* p, std::uint64_t key[4])
{
#if defined(__AVX__)
  const __m256d d = lanes::FromApex(InSphereApex(p), q[0], q[1], q[2], q[3]).distances2();
  const __m256d high = _mm256_castsi256_pd(_mm256_set1_epi64x(~std::int64_t(3)));
  const __m256d faces = _mm256_castsi256_pd(_mm256_set_epi64x(3, 2, 1, 0));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(key),
    _mm256_castpd_si256(_mm256_or_pd(_mm256_and_pd(d, high), faces)));
#else
  for (int k = 0; k < 4; ++k)
  {
    const double d = distance2(q[k], p);
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    key[k] = (bits & ~std::uint64_t(3)) | static_cast<std::uint64_t>(k);
  }
#endif
}

// The faces of a tetrahedron of vertices q, by decreasing distance from p to the vertex each
// leaves behind: a sorting network of five compare-exchanges without a branch, where a sort's
// branches were coin tosses to the predictor on every step of every walk. It sorts one integer
// per face: the squared distance's bits (non-negative doubles order as their bits do), the lowest
// two replaced by the face, so that the faces move with their keys.
void orderByDistance(const double* const q[4], const double* p, int order[4])
{
  std::uint64_t key[4];
  distanceKeys(q, p, key);
  // Written as a mask: as a minimum and a maximum, the compiler made a branch of each exchange.
  const auto exchange = [&](int i, int j) {
    const std::uint64_t swap = (key[i] ^ key[j]) & (std::uint64_t(0) - (key[i] < key[j]));
    key[i] ^= swap;
    key[j] ^= swap;
  };
  exchange(0, 1);
  exchange(2, 3);
  exchange(0, 2);
  exchange(1, 3);
  exchange(1, 2);
  for (int k = 0; k < 4; ++k)
    order[k] = static_cast<int>(key[k] & 3u);
}

// The face of a ghost, of hull face q, to cross on the way over the hull to p, or -1 where p lies
// over the hull face: of the three faces it shares with other ghosts, each on an edge of the hull
// face, the one across whose edge p's projection on the face's plane has its most negative
// barycentric coordinate, never the face the walk came in by. Each coordinate, scaled by the
// face's area, is a triple product with the face's normal. Floating point: the walk only needs a
// way, the predicates decide.
int hullFaceToward(const double* const q[3], const double* p, int entryFace)
{
  double e[3][3], r[3][3]; // e[k]: the edge opposite vertex k; r[k]: p from the edge's start
  for (int k = 0; k < 3; ++k)
  {
    const double* from = q[k == 2 ? 0 : k + 1];
    const double* to = q[k == 0 ? 2 : k - 1];
    for (int c = 0; c < 3; ++c)
    {
      e[k][c] = to[c] - from[c];
      r[k][c] = p[c] - from[c];
    }
  }
  double normal[3];
  cross(e[2], e[0], normal);
  int way = -1;
  double lowest = 0;
  for (int k = 0; k < 3; ++k)
  {
    double side[3];
    cross(e[k], r[k], side);
    const double coordinate = dot(side, normal);
    if (k != entryFace && coordinate < lowest)
    {
      lowest = coordinate;
      way = k;
    }
  }
  return way;
}
} // namespace

// The start: a tetrahedron of the inserted vertex nearest to the point among two candidates, the
// one the grid's onion search finds and the last inserted one (the curve order puts it close). On a
// surface sample the grid's cells are sized for volume and hold many points each, so the last
// vertex is often nearer; on volume data the grid's usually is.
TetId Inserter::startTet(VertId v, const BackgroundGrid::Cell& cell)
{
  if (restricted_)
    return regionStart(v, cell);
  VertId start = lastInserted_;
  if (mesh_.grid.enabled())
  {
    // A weighted mesh's grid may name a vertex hidden since.
    const VertId near = mesh_.weighted()
      ? mesh_.grid.nearestInserted(cell, kMaxOnionLayers,
          [this](VertId u) { return relaxedLoad(mesh_.vertices[u].tet) != kNoTet; })
      : mesh_.grid.nearestInserted(cell, kMaxOnionLayers);
    if (near != BackgroundGrid::kEmpty &&
      distance2(point(near), point(v)) < distance2(point(start), point(v)))
      start = near;
  }
  const TetId t = relaxedLoad(mesh_.vertices[start].tet);
  return t != kNoTet ? t : liveStart();
}

// Weighted, in a locking pass another inserter may hide this one's last vertex, or the grid's
// since it was read: the last tetrahedron this inserter made or started from instead. In a
// locking pass the walk takes it only if it is live (mayEnter()); alone, a dead one makes way for
// the first live slot.
TetId Inserter::liveStart()
{
  if (owners_ || !tets_.isDead(regionStart_))
    return regionStart_;
  TetId t = 0;
  while (tets_.isDead(t))
    ++t;
  return regionStart_ = t;
}

// In a region, the start must be the inserter's. The candidates are the region's tetrahedron near
// the last point (regionStart_) and the tetrahedron of the vertex of the region that the grid
// finds. Reading that one is safe: only this inserter changes the tetrahedron of a vertex of its
// region (it is always one of the vertex's), and a tetrahedron whose vertices 1 to 3 are in the
// region has three vertices in no other, so no other inserter writes it (nor its vertex 0, which
// shares a word with the flags). A region's points follow the whole set's curve out of its box and
// back in elsewhere, and on surface samples the curve also jumps across empty space: without the
// grid, walks on several threads crossed the region.
TetId Inserter::regionStart(VertId v, const BackgroundGrid::Cell& cell) const
{
  if (!mesh_.grid.enabled())
    return regionStart_;
  const double* p = point(v);
  // A weighted mesh's grid may name a vertex hidden since (in the region: by this inserter).
  const VertId near = mesh_.grid.nearestInserted(cell, kMaxOnionLayers,
    [this](VertId u) { return region_.contains(point(u)) && mesh_.vertices[u].tet != kNoTet; });
  if (near == BackgroundGrid::kEmpty)
    return regionStart_;
  VertId tv[4];
  tets_.vertices(regionStart_, tv);
  for (VertId u : tv)
    if (u != kInfinite && distance2(point(u), p) <= distance2(point(near), p))
      return regionStart_;
  const TetId t = relaxedLoad(mesh_.vertices[near].tet);
  for (int k = 1; k < 4; ++k)
    if (!inRegion(tets_.vertex(t, k)))
      return regionStart_;
  return inRegion(tets_.vertex(t, 0)) ? t : regionStart_;
}

// The walk at a ghost: whether it ends there, where the point lies beyond the hull face (with
// toFirstConflict, where the ghost is in conflict: on the face's plane, the tetrahedron behind it
// decides), else its next face: over the hull to the next ghost, or inside, from where the walk
// came onto the hull (in a locking pass, always inside). Where the hull's faces are needles (a
// cylinder's samples), a walk over them ends far from the point; a walk that ran out of hull steps
// halves the next ones' allowance, and one that found its way there raises it. A function of its
// own: inline in the walk's loop, it slowed the walk over volume data, which meets few ghosts.
Inserter::AtGhost Inserter::walkAtGhost(
  TetId ghost, VertId v, bool toFirstConflict, int entryFace, HullWalk& hull, FaceCode& next)
{
  VertId tv[4];
  tets_.vertices(ghost, tv);
  const double* q[3] = {point(tv[0]), point(tv[1]), point(tv[2])};
  const double* p = point(v);
  // Faces 0 to 2 of a ghost are shared with other ghosts, face 3 is the hull face.
  const bool cameOverHull = entryFace >= 0 && entryFace < 3;
  const int side = predicates_.orient3d(q[0], q[1], q[2], p);
  if (side > 0 || (side == 0 && toFirstConflict && onHullPlaneInConflict(ghost, v)))
  {
    if (cameOverHull)
      hullStepCap_ = std::min(kHullSteps, hullStepCap_ + 1);
    return AtGhost::Ends;
  }
  if (lockLost_)
    return AtGhost::Lost;
  if (!cameOverHull)
    hull.entry = tets_.neighbor(ghost, 3);
  // In a locking pass the walk holds only the tetrahedron it is in: the one behind the ghost where
  // it came onto the hull may be another inserter's by the time it would go back, or gone, and
  // going in from the last ghost made walks on a cylinder many times longer.
  const int way = owners_ ? -1 : hullFaceToward(q, p, entryFace);
  if (way >= 0 && hull.steps < hullStepCap_)
  {
    ++hull.steps;
    next = tets_.neighbor(ghost, way);
  }
  else
  {
    if (way >= 0) // out of hull steps
      hullStepCap_ = std::max(1, hullStepCap_ / 2);
    next = hull.entry;
  }
  return AtGhost::Steps;
}

// The visibility walk: until the current tetrahedron is in conflict (or, with a volume threshold or
// while looking for duplicates, contains the point or is a ghost whose hull face the point lies
// beyond), cross one of its faces that separates it from the point. In a region, a tetrahedron that
// is not the inserter's ends the walk with kNoTet (it was read safely: it shares a face with one
// that is). The faces are tried in order of decreasing distance from the point to the vertex they
// leave behind, so the tetrahedra close in on the point: on surface samples, whose thin tetrahedra
// fan out, a random first face made walks many times longer. From a ghost, the walk goes over the
// hull first, ghost to ghost (walkAtGhost()), while the point lies beyond an edge of the hull
// face: samples of a convex surface lie beyond the hull, near the last vertex, whose tetrahedron
// is a ghost; through the thin tetrahedra inside, an ellipsoid's walks took 1.5 times as many
// steps.
template <bool Weighted>
TetId Inserter::walk(TetId t, VertId v)
{
  const double* p = point(v);
  const auto probe = conflictProbe<Weighted>(v);
  const bool toFirstConflict = mesh_.options.volumeThreshold <= 0 && !lookForDuplicates_;
  int entryFace = -1;
  std::size_t steps = 0;
  HullWalk hull;
  for (;;)
  {
    if (++steps > kMaxSteps)
    {
      // In a parallel pass the mesh around may change: the point goes to a later, serial pass.
      t = restricted_ || owners_ ? kNoTet : scanForBase(v, toFirstConflict);
      break;
    }
    if (!mayEnter(t, entryFace))
    {
      t = kNoTet;
      break;
    }
    if (tets_.isGhost(t))
    {
      FaceCode next;
      const AtGhost at = walkAtGhost(t, v, toFirstConflict, entryFace, hull, next);
      if (at != AtGhost::Steps)
      {
        t = at == AtGhost::Ends ? t : kNoTet;
        break;
      }
      t = tetOf(next);
      entryFace = faceOf(next);
      continue;
    }
    VertId tv[4];
    tets_.vertices(t, tv);
    const double* q[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
    if (toFirstConflict && provenInConflict(probe, q, tv))
      break;
    int order[4];
    if (steps < kOrderedSteps)
      orderByDistance(q, p, order);
    else
    {
      const int first = static_cast<int>(nextRandom() & 3u);
      for (int k = 0; k < 4; ++k)
        order[k] = (first + k) & 3;
    }
    int exit = -1;
    for (int k = 0; k < 4 && exit < 0; ++k)
    {
      const int f = order[k];
      if (f == entryFace)
        continue;
      const double* saved = q[f];
      q[f] = p;
      if (predicates_.orient3d(q[0], q[1], q[2], q[3]) < 0)
        exit = f;
      q[f] = saved;
    }
    // No face separates t from the point: t contains it (the base).
    if (exit < 0)
      break;
    const FaceCode next = tets_.neighbor(t, exit);
    t = tetOf(next);
    entryFace = faceOf(next);
  }
  stats_.walkSteps += steps;
  stats_.maxWalkSteps = std::max(stats_.maxWalkSteps, steps);
  return t;
}

// Every live tetrahedron in turn until one where the walk may end: one in conflict with the point
// (the one that contains it is), or the one that contains it, or a ghost it lies beyond.
TetId Inserter::scanForBase(VertId v, bool toFirstConflict)
{
  for (TetId t = 0; t < tets_.slots(); ++t)
  {
    if (tets_.isDead(t))
      continue;
    if (toFirstConflict    ? inConflict(t, v)
        : tets_.isGhost(t) ? isBeyondHullFace(t, v)
                           : holdsPoint(t, v))
      return t;
  }
  return kNoTet;
}

TetId Inserter::locate(VertId v, const BackgroundGrid::Cell& cell)
{
  return mesh_.weighted() ? walk<true>(startTet(v, cell), v) : walk<false>(startTet(v, cell), v);
}

// A point repeating a vertex w lies in a closed tetrahedron only if w is one of its vertices (the
// mesh is a simplicial complex), and never beyond a hull face.
VertId Inserter::repeatedVertex(TetId base, VertId v) const
{
  if (tets_.isGhost(base))
    return kNoVertex;
  const double* p = point(v);
  for (int k = 0; k < 4; ++k)
  {
    const double* q = point(tets_.vertex(base, k));
    if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2])
      return tets_.vertex(base, k);
  }
  return kNoVertex;
}

} // namespace fd3
