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
  const Vertex* p = mesh_.vertices.data();
  const double* q[4] = {p[tv[0]].xyz, p[tv[1]].xyz, p[tv[2]].xyz, p[tv[3]].xyz};
  double weights[4];
  weightsOf(tv, weights);
  return conflictProbe<true>(v).inside(q, weights);
}

// Only a vertex whose own tetrahedron (Vertex::tet) the cavity deletes can lose all of them: each
// vertex is a candidate in one deleted tetrahedron at most, whose record, and the vertex's, the
// cavity's tests have in cache. Every vertex of the cavity is written to the list and only the
// candidates are kept (the count advances by the test's outcome): a branch on the outcome is a
// coin toss to the predictor, and a push_back under it costs about twenty instructions a vertex.
void Inserter::collectCavityVertices()
{
  const std::size_t deleted = cavity_.deleted.size();
  if (cavityVertices_.size() < 4 * deleted)
    cavityVertices_.resize(4 * deleted);
  CavityVertex* const out = cavityVertices_.data();
  const TetReader tets = tets_.records();
  const Vertex* const vertices = mesh_.vertices.data();
  std::size_t count = 0;
  for (const FaceCode c : cavity_.deleted)
  {
    const TetId t = tetOf(c);
    VertId tv[4];
    tets.vertices(t, tv);
    const auto candidate = [&](VertId u) {
      return static_cast<std::size_t>(relaxedLoad(vertices[u].tet) == t);
    };
    // Only vertex 3 may be the ghost vertex, which has no record: vertex 0's is read instead.
    const std::size_t finite3 = tv[3] != kInfinite;
    out[count] = {tv[0], t};
    count += candidate(tv[0]);
    out[count] = {tv[1], t};
    count += candidate(tv[1]);
    out[count] = {tv[2], t};
    count += candidate(tv[2]);
    out[count] = {tv[3], t};
    count += finite3 & candidate(finite3 ? tv[3] : tv[0]);
  }
  cavityCandidates_ = count;
}

// A candidate on the cavity's boundary got one of the new tetrahedra from the fill (never a
// deleted one: the new ones came from the pool before those went back to it), and in a locking
// pass another inserter may have given it one of its own since; a candidate whose tetrahedron is
// still the deleted one lies inside the cavity, on no tetrahedron left. Comparing the one word
// reads no record that another inserter may be writing.
void Inserter::hideEnclosedVertices()
{
  for (std::size_t k = 0; k < cavityCandidates_; ++k)
  {
    const CavityVertex& candidate = cavityVertices_[k];
    if (relaxedLoad(mesh_.vertices[candidate.vertex].tet) == candidate.tet)
    {
      hide(candidate.vertex);
      --stats_.insertedPoints; // inserted by this inserter or another: the sum is right
    }
  }
}

void Inserter::hide(VertId u)
{
  setVertexTet(u, kNoTet);
  hidden_.push_back(u);
  ++stats_.hiddenPoints;
}

} // namespace fd3
