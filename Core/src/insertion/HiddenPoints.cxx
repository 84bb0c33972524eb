// Weighted points: the regular tetrahedralization's hidden points, both ways. A new point that
// conflicts with no tetrahedron is hidden and never becomes a vertex; a vertex whose every
// tetrahedron a heavier point's cavity takes lies on none of the new ones, and leaves the mesh.
// Bowyer-Watson does both without a change to the cavity or the fill: these steps only tell them
// apart and record them.
#include "insertion/Inserter.h"

namespace fd3
{

bool Inserter::baseInConflict(TetId base, VertId v)
{
  if (tets_.isGhost(base))
    return true; // beyond the hull, where no point is hidden
  VertId tv[4];
  tets_.vertices(base, tv);
  return conflictSoS(tv, v) > 0;
}

void Inserter::collectCavityVertices(VertId v)
{
  if (vertexStamp_.size() < mesh_.vertices.size())
    vertexStamp_.resize(mesh_.vertices.size(), 0);
  ++stamp_;
  vertexStamp_[v] = stamp_;
  cavityVertices_.clear();
  for (const FaceCode c : cavity_.deleted)
    for (int i = 0; i < 4; ++i)
    {
      const VertId u = tets_.vertex(tetOf(c), i);
      if (u != kInfinite && vertexStamp_[u] != stamp_)
      {
        vertexStamp_[u] = stamp_;
        cavityVertices_.push_back(u);
      }
    }
}

// The fill gave every vertex of the cavity's boundary one of the new tetrahedra; a vertex of the
// cavity still on one of the deleted ones is on no tetrahedron left.
void Inserter::hideEnclosedVertices()
{
  for (const VertId u : cavityVertices_)
    if (tets_.isDead(relaxedLoad(mesh_.vertices[u].tet)))
    {
      hide(u);
      --stats_.insertedPoints; // inserted by this inserter or another: the sum is right
    }
}

void Inserter::hide(VertId u)
{
  setVertexTet(u, kNoTet);
  hidden_.push_back(u);
  ++stats_.hiddenPoints;
}

} // namespace fd3
