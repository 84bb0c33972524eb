// Growing the cavity (the paper's core): from a tetrahedron in conflict, through adjacency, every
// tetrahedron whose circumsphere contains the new point (exact insphere, ties broken
// symbolically). With exact predicates the conflict zone is connected, so growing it from any of
// its tetrahedra finds all of it.
#include "Inserter.h"

namespace fd3
{

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
  tets_.vertices(tetOf(tets_.neighbor(ghost, 3)), tv);
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
// inserter's (in a region).
bool Inserter::digCavity(TetId base, VertId v)
{
  cavity_.clear();
  std::vector<TetId>& tets = cavity_.tets;
  tets_.setFlags(base, kInCavity);
  tets.push_back(base);
  for (int f = 0; f < 4; ++f)
    tets_.prefetch(tetOf(tets_.neighbor(base, f)));
  for (std::size_t i = 0; i < tets.size(); ++i)
  {
    const TetId t = tets[i];
    // The neighbours' records were requested when t joined. Their points are not: a neighbour
    // shares three of them with t, which its test has just read.
    for (int f = 0; f < 4; ++f)
    {
      const TetId n = tetOf(tets_.neighbor(t, f));
      const std::uint32_t flag = tets_.flags(n);
      if (flag == kInCavity)
        continue;
      if (flag == 0)
      {
        if (inConflict(n, v))
        {
          tets_.setFlags(n, kInCavity);
          tets.push_back(n);
          if (!isOwned(n))
          {
            undoCavity();
            return false;
          }
          for (int g = 0; g < 4; ++g)
            tets_.prefetch(tetOf(tets_.neighbor(n, g)));
          continue;
        }
        tets_.setFlags(n, kNotInCavity);
        cavity_.rejected.push_back(n);
      }
      // Field by field in place: push_back({t, f}) spilled t and f to the stack as two 4-byte
      // stores and reloaded them as one 8-byte value, which stalls store forwarding (a fifth of
      // this function's samples on the 1M cube).
      BoundaryFacet& facet = cavity_.boundary.emplace_back();
      facet.inner = t;
      facet.face = f;
    }
  }
  stats_.cavityTetrahedra += tets.size();
  return true;
}

} // namespace fd3
