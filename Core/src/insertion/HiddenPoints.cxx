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

// Every vertex of every deleted tetrahedron, repeats too: their records are in cache from the
// cavity's tests, where a mark per vertex to list each once would be another array to miss in.
void Inserter::collectCavityVertices()
{
  cavityVertices_.clear();
  for (const FaceCode c : cavity_.deleted)
    for (int i = 0; i < 4; ++i)
      if (const VertId u = tets_.vertex(tetOf(c), i); u != kInfinite)
        cavityVertices_.push_back(u);
}

// The fill gave every vertex of the cavity's boundary one of the new tetrahedra; a vertex of the
// cavity still on one of the deleted ones is on no tetrahedron left (and hidden once: hide()
// leaves it on none).
void Inserter::hideEnclosedVertices()
{
  for (const VertId u : cavityVertices_)
    if (const TetId t = relaxedLoad(mesh_.vertices[u].tet); t != kNoTet && tets_.isDead(t))
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
