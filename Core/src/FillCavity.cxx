// Filling the cavity: one new tetrahedron per boundary facet, joining the facet to the new point,
// linked to its neighbours without any search over the mesh. The neighbour across a new face
// (p, u, w) is the other new tetrahedron on the boundary edge uw: found in a table of the
// boundary's directed edges (the paper's one-to-one correspondence of section 3.3 between new
// tetrahedra and boundary facets), or, for cavities with more boundary vertices than the table
// takes, by rotating about uw through the deleted tetrahedra as the paper does. The table grows
// with the cavity: surface samples make cavities of hundreds of tetrahedra (cylinder, 1M points:
// 74 deleted per insertion on average), and rotating about their long edges cost more than the
// rest of the insertion.
#include "Inserter.h"

#include <array>

namespace fd3
{
namespace
{
// The interior faces of a new tetrahedron whose vertex g is the new point: each face f != g, with
// the directed boundary edge a->b it holds (its outward order kFaceVertices[f], rotated to start
// at g). The two new tetrahedra on one boundary edge hold it in opposite directions.
struct InteriorFace
{
  int face, a, b;
};
constexpr std::array<std::array<InteriorFace, 3>, 4> interiorFaces()
{
  std::array<std::array<InteriorFace, 3>, 4> table{};
  for (int g = 0; g < 4; ++g)
  {
    int j = 0;
    for (int f = 0; f < 4; ++f)
    {
      if (f == g)
        continue;
      const int* v = kFaceVertices[f];
      const int r = v[0] == g ? 0 : (v[1] == g ? 1 : 2);
      table[g][j++] = {f, v[(r + 1) % 3], v[(r + 2) % 3]};
    }
  }
  return table;
}
constexpr auto kInterior = interiorFaces();

// During a fill, the tet field of each boundary vertex holds kLocalTag | its local number. Every
// tetrahedron id is below 2^30 and kNoTet (a vertex yet to be inserted) has other high bits, so
// the high half tells a number from a tetrahedron.
constexpr TetId kLocalTag = 0x80000000u;
constexpr TetId kHighHalf = 0xFFFF0000u;
} // namespace

// Returns false, undoing everything, when the mesh has no room left for the new tetrahedra.
bool Inserter::fillCavity(VertId v)
{
  std::vector<TetId>& created = cavity_.created;
  created.resize(cavity_.boundary.size());
  if (!pool_.take(tets_, created.size(), created.data()))
  {
    undoCavity();
    return false;
  }
  if (!createAndLink(v))
  {
    // More boundary vertices than the edge table takes: the new tetrahedra exist and are linked
    // across the boundary; each interior face is linked by rotating about its boundary edge.
    for (std::size_t i = 0; i < created.size(); ++i)
    {
      VertId nv[4];
      tets_.vertices(created[i], nv);
      for (int k = 0; k < 4; ++k)
        if (nv[k] != kInfinite)
          mesh_.vertices[nv[k]].tet = created[i];
      for (int f = 0; f < 4; ++f)
        if (f != cavity_.boundary[i].face && tets_.neighbor(created[i], f) == kUnlinked)
          linkAroundEdge(i, f);
    }
  }
  for (TetId t : cavity_.tets)
    pool_.give(tets_, t);
  for (TetId t : cavity_.rejected)
    tets_.setFlags(t, 0);
  regionStart_ = created.back();
  return true;
}

// One pass over the boundary facets. The new tetrahedron of facet (t, f) is t with vertex f
// replaced by v, which keeps the orientation positive because v sees the facet from t's side; it is
// linked to the tetrahedron across the facet, and the deleted t's slot for face f is pointed at it
// (how the rotation of linkAroundEdge recognizes a boundary facet). Its three faces through v are
// recorded at their directed boundary edges a->b and, once every facet is done, linked to the face
// recorded at b->a. Edges are indexed by local numbers of the boundary's vertices, given on first
// sight through localNumberSlot() without a branch (a new vertex takes number `count`, which only
// advances then); v takes one too, which costs less than a branch on which vertex it is. The
// boundary is a triangulated sphere, so its vertices number F/2 + 2 for F facets (Euler), which
// sizes the table before the pass. Returns false, with every new tetrahedron created and linked
// across the boundary but not to each other, when the table is too small.
bool Inserter::createAndLink(VertId v)
{
  const std::vector<TetId>& created = cavity_.created;
  std::vector<VertId>& vertexOf = cavity_.localVertex;
  std::vector<TetId>& firstTet = cavity_.localTet;
  const std::uint32_t expected = static_cast<std::uint32_t>(created.size() / 2 + 3); // with v
  std::uint32_t width = 16;
  while (width < expected)
    width *= 2;
  const bool fits = expected <= Cavity::kMaxLocalVertices;
  if (fits && cavity_.edgeFace.size() < std::size_t(width) * width)
    cavity_.edgeFace.resize(std::size_t(width) * width);
  vertexOf.resize(width + 4);
  firstTet.resize(width + 4);
  cavity_.interiorFaces.resize(3 * created.size());
  std::uint32_t count = 0;
  bool linked = fits;
  for (std::size_t i = 0; i < created.size(); ++i)
  {
    const BoundaryFacet b = cavity_.boundary[i];
    const TetId n = created[i];
    VertId tv[4];
    tets_.vertices(b.inner, tv);
    // Vertex b.face replaced by masks, neither by a store into tv (a narrow store then a wide
    // reload of the same bytes, which stalls store forwarding) nor by a branch on b.face (a coin
    // toss to the predictor): GCC turns both plain forms into one or the other.
    VertId nv[4];
    for (int k = 0; k < 4; ++k)
    {
      const VertId replace = 0u - VertId(k == b.face);
      nv[k] = (tv[k] & ~replace) | (v & replace);
    }
    tets_.create(n, nv);
    tets_.link(faceCode(n, b.face), tets_.neighbor(b.inner, b.face));
    tets_.setNeighbor(faceCode(b.inner, b.face), faceCode(n, b.face));
    if (!linked)
      continue;
    std::uint32_t local[4];
    for (int k = 0; k < 4; ++k)
    {
      const VertId u = nv[k];
      TetId& entry = localNumberSlot(u);
      const bool isNew = (entry & kHighHalf) != kLocalTag;
      local[k] = isNew ? count : (entry & 0xFFFFu);
      entry = kLocalTag | local[k];
      vertexOf[count] = u;
      firstTet[count] = n;
      count += isNew;
    }
    if (count > width)
    {
      linked = false; // not a sphere after all: the numbers would leave the table
      continue;
    }
    for (int j = 0; j < 3; ++j)
    {
      const InteriorFace& face = kInterior[b.face][j];
      const std::uint32_t from = local[face.a], to = local[face.b];
      cavity_.edgeFace[from * width + to] = faceCode(n, face.face);
      cavity_.interiorFaces[3 * i + j] = {faceCode(n, face.face), to * width + from};
    }
  }
  // Each vertex gets one of its new tetrahedra in place of its number.
  for (std::uint32_t k = 0; k < count; ++k)
    localNumberSlot(vertexOf[k]) = firstTet[k];
  ghostTet_ = kNoTet;
  if (!linked)
    return false;
  for (const auto& [face, reversed] : cavity_.interiorFaces)
    tets_.setNeighbor(face, cavity_.edgeFace[reversed]);
  return true;
}

// New tetrahedron i was built on boundary facet (t, g); its face `face` holds the new point and
// the facet's edge uw. Turn about uw through the deleted tetrahedra, starting with t's other face on
// uw, until a boundary facet is met: the new tetrahedron built on it is the neighbour.
void Inserter::linkAroundEdge(std::size_t i, int face)
{
  const BoundaryFacet& facet = cavity_.boundary[i];
  // Local indices of u and w (the same in t and in its new tetrahedron): the two of 0..3 that are
  // neither `face` nor `facet.face`, as the two bit positions left in a 4-bit mask.
  const unsigned rest = 15u & ~(1u << face) & ~(1u << facet.face);
  int iu = countTrailingZeros(rest);
  int iw = countTrailingZeros(rest & (rest - 1));
  const VertId u = tets_.vertex(facet.inner, iu);
  const VertId w = tets_.vertex(facet.inner, iw);

  TetId t = facet.inner;
  int g = face; // the face of t being crossed; it contains u and w
  for (;;)
  {
    const FaceCode across = tets_.neighbor(t, g);
    const TetId next = tetOf(across);
    if (tets_.flags(next) != kInCavity)
    {
      // (t, g) is a boundary facet and `next` its new tetrahedron: t with vertex g replaced by the
      // new point, whose face on (point, u, w) is opposite t's fourth vertex.
      tets_.link(faceCode(cavity_.created[i], face), faceCode(next, 6 - g - iu - iw));
      return;
    }
    VertId nv[4];
    tets_.vertices(next, nv);
    iu = (nv[1] == u) + 2 * (nv[2] == u) + 3 * (nv[3] == u);
    iw = (nv[1] == w) + 2 * (nv[2] == w) + 3 * (nv[3] == w);
    g = 6 - faceOf(across) - iu - iw;
    t = next;
  }
}

} // namespace fd3
