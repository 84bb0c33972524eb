// Growing the cavity (the paper's core): from a tetrahedron in conflict, through adjacency, every
// tetrahedron whose circumsphere contains the new point (exact insphere, ties broken
// symbolically). With exact predicates the conflict zone is connected, so growing it from any of
// its tetrahedra finds all of it.
#include "insertion/Inserter.h"

#include <algorithm>
#include <cassert>

namespace fd3
{
namespace
{
// Room in `list` for more than twice `count` elements, the first `count` kept.
template <typename T>
T* grow(ScratchVector<T>& list, std::size_t count)
{
  list.resize(std::max<std::size_t>(2 * count + 4, 64));
  return list.data();
}

// The faces of a tetrahedron other than the one it was entered through; the last row, for the
// base, lists all four.
constexpr std::uint8_t kNoEntryFace = 4;
constexpr int kFacesBesides[5][4] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}, {0, 1, 2, 3}};
} // namespace

bool Inserter::isBeyondHullFace(TetId ghost, VertId v)
{
  VertId tv[4];
  tets_.vertices(ghost, tv);
  return predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(v)) > 0;
}

// A ghost's circumsphere is the open half-space beyond its hull face. A point on the face's plane
// takes the verdict of the finite tetrahedron behind the face, so that the two never disagree and
// no flat tetrahedron is created.
bool Inserter::ghostInConflict(TetId ghost, VertId v)
{
  VertId tv[4];
  tets_.vertices(ghost, tv);
  const int side = predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(v));
  if (side != 0)
    return side > 0;
  const TetId behind = tetOf(tets_.neighbor(ghost, 3));
  if (owners_ && !acquire(behind))
  {
    lockLost_ = true; // another inserter's: the insertion is put off
    return false;
  }
  tets_.vertices(behind, tv);
  return inSphereSoS(tv, v) > 0;
}

void Inserter::undoCavity()
{
  for (TetId t : cavity_.tets)
    tets_.setFlags(t, 0);
  for (TetId t : cavity_.rejected)
    tets_.setFlags(t, 0);
}

// Returns false, undoing everything, when the cavity reaches a tetrahedron that is not the
// inserter's: in a region, one with a vertex outside it (the faces of the tetrahedron at hand are
// still tested, which reads only its neighbours: three vertices in the region, no other inserter
// writes them); in a locking pass, one that another inserter holds (not read at all).
//
// No branch depends on a test's outcome, a coin toss to the predictor: the outcome only picks the
// flag written and which list's count advances (the lists have room for every face of the
// tetrahedron at hand). Behind a mispredicted branch, the processor threw away the next tests it
// had started while the determinant was computed.
bool Inserter::digCavity(TetId base, VertId v)
{
  cavity_.clear();
  std::size_t inCavity = 1, kept = 0, facets = 0;
  TetId* tets = grow(cavity_.tets, 0);
  std::uint8_t* entry = grow(cavity_.entryFace, 0);
  TetId* rejected = grow(cavity_.rejected, 0);
  BoundaryFacet* boundary = grow(cavity_.boundary, 0);
  assert(mayTouch(base));
  tets_.setFlags(base, kInCavity);
  tets[0] = base;
  entry[0] = kNoEntryFace;
  for (int f = 0; f < 4; ++f)
    prefetchTet(tetOf(tets_.neighbor(base, f)));
  bool owned = true;
  for (std::size_t i = 0; i < inCavity; ++i)
  {
    if (cavity_.tets.size() < inCavity + 4)
    {
      tets = grow(cavity_.tets, inCavity);
      entry = grow(cavity_.entryFace, inCavity);
    }
    if (cavity_.rejected.size() < kept + 4)
      rejected = grow(cavity_.rejected, kept);
    if (cavity_.boundary.size() < facets + 4)
      boundary = grow(cavity_.boundary, facets);
    const TetId t = tets[i];
    // The face t was reached through leads back into the cavity: a fixed three faces are visited
    // (four for the base), not four with a skip whose position is random.
    const int* faces = kFacesBesides[entry[i]];
    const int count = entry[i] == kNoEntryFace ? 4 : 3;
    for (int k = 0; k < count; ++k)
    {
      const int f = faces[k];
      const FaceCode across = tets_.neighbor(t, f);
      const TetId n = tetOf(across);
      if (owners_ && !acquire(n))
      {
        lockLost_ = true; // another inserter's: not even its flags may be read
        break;
      }
      const std::uint32_t flag = tets_.flags(n);
      if (flag == kInCavity)
        continue;
      bool inside = false;
      if (flag == 0)
      {
        inside = inConflict(n, v) && !lockLost_;
        assert(mayTouch(n));
        tets_.setFlags(n, inside ? kInCavity : kNotInCavity);
        tets[inCavity] = n;
        entry[inCavity] = static_cast<std::uint8_t>(faceOf(across));
        inCavity += inside;
        rejected[kept] = n;
        kept += !inside;
        // The neighbours of every tested tetrahedron, kept ones too: a prefetch chosen by the
        // outcome would wait for the determinant.
        for (int g = 0; g < 4; ++g)
          prefetchTet(tetOf(tets_.neighbor(n, g)));
        // n shares with t, whose four vertices are in the region, all but the one opposite.
        if (restricted_)
          owned &= !inside || inRegion(tets_.vertex(n, faceOf(across)));
      }
      // Field by field: a whole BoundaryFacet spilled t and f to the stack as two 4-byte stores
      // and reloaded them as one 8-byte value, which stalls store forwarding.
      boundary[facets].inner = t;
      boundary[facets].face = f;
      facets += !inside;
    }
    if (!owned || lockLost_)
      break;
  }
  cavity_.tets.resize(inCavity);
  cavity_.rejected.resize(kept);
  cavity_.boundary.resize(facets);
  if (!owned || lockLost_)
  {
    undoCavity();
    return false;
  }
  stats_.cavityTetrahedra += inCavity;
  return true;
}

} // namespace fd3
