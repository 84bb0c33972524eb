// Filling the core: one new tetrahedron per boundary facet, joining the facet to the new point,
// linked to its neighbours without any search: the neighbour across a new face (p, u, v) is found by
// rotating about the boundary edge uv through the deleted tetrahedra (the paper's section 3.3).
#include "Triangulator.h"

namespace fd3
{

void Triangulator::fillCavity(VertId v)
{
  created_.clear();
  // Pass 1: create the tetrahedra and link them across the core's boundary. The new tetrahedron of
  // facet (t, f) is t with vertex f replaced by v, which keeps the orientation positive because v
  // sees the facet from t's side. The deleted t's slot for face f is pointed at the new
  // tetrahedron, which is how pass 2 recognizes a boundary facet and finds its tetrahedron.
  for (const BoundaryFacet& b : boundary_)
  {
    const TetId n = mesh_.allocate();
    VertId tv[4];
    mesh_.vertices(b.inner, tv);
    tv[b.face] = v;
    for (int i = 0; i < 4; ++i)
    {
      mesh_.setVertex(n, i, tv[i]);
      mesh_.setNeighbor(faceCode(n, i), kUnlinked);
      if (tv[i] != kInfinite)
        vertexTet_[tv[i]] = n;
    }
    mesh_.link(faceCode(n, b.face), mesh_.neighbor(b.inner, b.face));
    mesh_.setNeighbor(faceCode(b.inner, b.face), faceCode(n, b.face));
    created_.push_back(n);
  }
  // Pass 2: link the new tetrahedra to each other.
  for (std::size_t i = 0; i < created_.size(); ++i)
    for (int f = 0; f < 4; ++f)
      if (f != boundary_[i].face && mesh_.neighbor(created_[i], f) == kUnlinked)
        linkAroundEdge(i, f);

  for (TetId t : cavity_)
    mesh_.release(t);
  for (TetId t : rejected_)
    mesh_.setFlags(t, 0);
  lastCreated_ = created_.back();
}

// New tetrahedron i was built on boundary facet (t, g); its face `face` holds the new point and
// the facet's edge uw. Turn about uw through the deleted tetrahedra, starting with t's other face on
// uw, until a boundary facet is met: the new tetrahedron built on it is the neighbour.
void Triangulator::linkAroundEdge(std::size_t i, int face)
{
  const BoundaryFacet& facet = boundary_[i];
  // Local indices of u and w (the same in t and in its new tetrahedron): the two of 0..3 that are
  // neither `face` nor `facet.face`, as the two bit positions left in a 4-bit mask.
  const unsigned rest = 15u & ~(1u << face) & ~(1u << facet.face);
  int iu = __builtin_ctz(rest);
  int iw = __builtin_ctz(rest & (rest - 1));
  const VertId u = mesh_.vertex(facet.inner, iu);
  const VertId w = mesh_.vertex(facet.inner, iw);

  TetId t = facet.inner;
  int g = face; // the face of t being crossed; it contains u and w
  for (;;)
  {
    const FaceCode across = mesh_.neighbor(t, g);
    const TetId next = tetOf(across);
    if (mesh_.flags(next) != kInCavity)
    {
      // (t, g) is a boundary facet and `next` its new tetrahedron: t with vertex g replaced by the
      // new point, whose face on (point, u, w) is opposite t's fourth vertex.
      mesh_.link(faceCode(created_[i], face), faceCode(next, 6 - g - iu - iw));
      return;
    }
    VertId nv[4];
    mesh_.vertices(next, nv);
    iu = (nv[1] == u) + 2 * (nv[2] == u) + 3 * (nv[3] == u);
    iw = (nv[1] == w) + 2 * (nv[2] == w) + 3 * (nv[3] == w);
    g = 6 - faceOf(across) - iu - iw;
    t = next;
  }
}

} // namespace fd3
