// The paper's correction of the core (section 2.3): every facet of the core's boundary must be
// visible from the new point, so that the core is star-shaped and every new tetrahedron positive;
// with a volume threshold, no new tetrahedron may be flatter than the threshold (the sliver
// guard). A facet that fails gives its inner tetrahedron back to the mesh, which shrinks the core,
// until every facet passes. An existing vertex left strictly inside the core would vanish with it:
// one of its tetrahedra is given back too (the paper's Fig. 7).
//
// With an exact Delaunay core (threshold 0) both conditions hold by construction: the conflict
// zone of exact, symbolically perturbed predicates is star-shaped, and every point is a vertex of
// the Delaunay triangulation. The correction then has nothing to do and is skipped; checkMesh
// verifies the outcome in the tests.
#include "insertion/Inserter.h"

#include "fd3/Measures.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace fd3
{

// Tetrahedra whose closure holds the new point can never be given back: the point would be left
// outside the core. Only finite ones qualify; ghosts are handled by their hull face below.
bool Inserter::holdsPoint(TetId t, VertId v)
{
  if (tets_.isGhost(t))
    return false;
  VertId tv[4];
  tets_.vertices(t, tv);
  for (int i = 0; i < 4; ++i)
  {
    const double* q[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
    q[i] = point(v);
    if (predicates_.orient3d(q[0], q[1], q[2], q[3]) < 0)
      return false;
  }
  return true;
}

// Shape of the tetrahedron the facet would make with the new point: its volume relative to the
// regular tetrahedron on its longest edge (1 for a regular tetrahedron, 0 when flat), or a negative
// value when the point does not see the facet. Ghost results (hull faces) have no volume: 1.
double Inserter::newTetShape(FaceCode facet, VertId v)
{
  VertId tv[4];
  tets_.vertices(tetOf(facet), tv);
  tv[faceOf(facet)] = v;
  if (tv[3] == kInfinite)
    return 1.0;
  const double* q[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
  if (predicates_.orient3d(q[0], q[1], q[2], q[3]) <= 0)
    return -1.0;
  double longest = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      longest = std::max(longest, distance2(q[i], q[j]));
  // The regular tetrahedron of edge L has six times its volume equal to L^3 / sqrt(2).
  return sixVolume(q[0], q[1], q[2], q[3]) * std::sqrt(2.0) / (longest * std::sqrt(longest));
}

void Inserter::giveBack(TetId t)
{
  assert(mayTouch(t));
  tets_.setFlags(t, kNotInCavity);
  cavity_.rejected.push_back(t);
}

void Inserter::collectBoundary()
{
  ScratchList<FaceCode>& deleted = cavity_.deleted;
  deleted.resize(std::remove_if(deleted.begin(), deleted.end(),
                   [&](FaceCode c) { return tets_.flags(tetOf(c)) != kInCavity; }) -
    deleted.begin());
  // The fill clears the flags of the tetrahedra across the boundary. A facet leaves it when its
  // inner tetrahedron leaves the cavity: the one across is listed, to be cleared with the rest.
  for (const FaceCode b : cavity_.boundary)
    if (tets_.flags(tetOf(b)) != kInCavity)
      cavity_.rejected.push_back(tetOf(tets_.across(b)));
  cavity_.boundary.clear();
  for (FaceCode c : deleted)
  {
    const TetId t = tetOf(c);
    for (int f = 0; f < 4; ++f)
      if (tets_.flags(tetOf(tets_.neighbor(t, f))) != kInCavity)
        cavity_.boundary.push_back(faceCode(t, f));
  }
}

// A ghost kept only because its hull face is coplanar with the point (the tie rule of
// inConflict) must leave with the finite tetrahedron behind that face.
bool Inserter::dropOrphanGhosts(VertId v)
{
  bool changed = false;
  for (FaceCode c : cavity_.deleted)
  {
    const TetId t = tetOf(c);
    if (tets_.flags(t) != kInCavity || !tets_.isGhost(t) ||
      tets_.flags(tetOf(tets_.neighbor(t, 3))) == kInCavity)
      continue;
    VertId tv[4];
    tets_.vertices(t, tv);
    if (predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(v)) == 0)
    {
      giveBack(t);
      changed = true;
    }
  }
  return changed;
}

// A vertex of the core that lies on none of its boundary facets would disappear: one of its
// tetrahedra is given back, which keeps the vertex in the mesh.
bool Inserter::keepEnclosedVertex(VertId v)
{
  ++stamp_;
  for (const FaceCode b : cavity_.boundary)
    for (int i = 0; i < 4; ++i)
      if (i != faceOf(b) && tets_.vertex(tetOf(b), i) != kInfinite)
        vertexStamp_[tets_.vertex(tetOf(b), i)] = stamp_;
  for (FaceCode c : cavity_.deleted)
  {
    const TetId t = tetOf(c);
    for (int i = 0; i < 4; ++i)
    {
      const VertId u = tets_.vertex(t, i);
      if (u != kInfinite && vertexStamp_[u] != stamp_ && !holdsPoint(t, v))
      {
        giveBack(t);
        return true;
      }
    }
  }
  return false;
}

void Inserter::correctCavity(VertId v)
{
  if (mesh_.options.volumeThreshold <= 0)
    return;
  if (vertexStamp_.empty())
    vertexStamp_.assign(mesh_.vertices.size(), 0);
  for (bool changed = true; changed;)
  {
    changed = false;
    for (const FaceCode b : cavity_.boundary)
    {
      const TetId inner = tetOf(b);
      if (tets_.flags(inner) != kInCavity || tets_.isGhost(inner))
        continue;
      if (newTetShape(b, v) < mesh_.options.volumeThreshold && !holdsPoint(inner, v))
      {
        giveBack(inner);
        changed = true;
      }
    }
    changed |= dropOrphanGhosts(v);
    if (!changed)
      changed = keepEnclosedVertex(v);
    if (changed)
      collectBoundary();
  }
}

} // namespace fd3
