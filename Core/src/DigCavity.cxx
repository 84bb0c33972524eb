// Growing the cavity (the paper's core): from a tetrahedron in conflict, through adjacency, every
// tetrahedron whose circumsphere contains the new point (exact insphere, ties broken
// symbolically). With exact predicates the conflict zone is connected, so growing it from any of
// its tetrahedra finds all of it.
#include "Triangulator.h"

#include "fd3/Measures.h"

namespace fd3
{

bool Triangulator::isBeyondHullFace(TetId ghost, VertId v)
{
  VertId tv[4];
  mesh_.vertices(ghost, tv);
  return predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(v)) > 0;
}

bool Triangulator::inConflict(TetId t, VertId v)
{
  VertId tv[4];
  mesh_.vertices(t, tv);
  if (tv[3] != kInfinite)
    return inSphereSoS(tv, v) > 0;
  // A ghost's circumsphere is the open half-space beyond its hull face. A point on the face's
  // plane takes the verdict of the finite tetrahedron behind the face, so that the two never
  // disagree and no flat tetrahedron is created.
  const int side = predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(v));
  if (side != 0)
    return side > 0;
  mesh_.vertices(tetOf(mesh_.neighbor(t, 3)), tv);
  return inSphereSoS(tv, v) > 0;
}

// The point's nearest inserted neighbour is a Delaunay neighbour of it, so a vertex of the cavity:
// looking there is enough to honour the tolerance.
VertId Triangulator::vertexWithin(double distance2, VertId v) const
{
  for (const BoundaryFacet& b : cavity_.boundary)
    for (int i = 0; i < 4; ++i)
    {
      const VertId u = mesh_.vertex(b.inner, i);
      if (i != b.face && u != kInfinite && fd3::distance2(point(u), point(v)) < distance2)
        return u;
    }
  return kNoVertex;
}

void Triangulator::undoCavity()
{
  for (TetId t : cavity_.tets)
    mesh_.setFlags(t, 0);
  for (TetId t : cavity_.rejected)
    mesh_.setFlags(t, 0);
}

void Triangulator::digCavity(TetId base, VertId v)
{
  cavity_.clear();
  std::vector<TetId>& tets = cavity_.tets;
  mesh_.setFlags(base, kInCavity);
  tets.push_back(base);
  for (int f = 0; f < 4; ++f)
    mesh_.prefetch(tetOf(mesh_.neighbor(base, f)));
  for (std::size_t i = 0; i < tets.size(); ++i)
  {
    const TetId t = tets[i];
    // The neighbours' records were requested when t joined; now their points, all at once.
    for (int f = 0; f < 4; ++f)
    {
      const TetId n = tetOf(mesh_.neighbor(t, f));
      if (mesh_.flags(n) != 0)
        continue;
      VertId nv[4];
      mesh_.vertices(n, nv);
      for (int k = 0; k < 4; ++k)
        if (nv[k] != kInfinite)
          fd3::prefetch(point(nv[k]));
    }
    for (int f = 0; f < 4; ++f)
    {
      const TetId n = tetOf(mesh_.neighbor(t, f));
      const std::uint32_t flag = mesh_.flags(n);
      if (flag == kInCavity)
        continue;
      if (flag == 0)
      {
        if (inConflict(n, v))
        {
          mesh_.setFlags(n, kInCavity);
          tets.push_back(n);
          for (int g = 0; g < 4; ++g)
            mesh_.prefetch(tetOf(mesh_.neighbor(n, g)));
          continue;
        }
        mesh_.setFlags(n, kNotInCavity);
        cavity_.rejected.push_back(n);
      }
      cavity_.boundary.push_back({t, f});
    }
  }
  stats_.cavityTetrahedra += tets.size();
}

} // namespace fd3
