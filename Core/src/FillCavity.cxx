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
  // Pass 1: create the tetrahedra and link them across the cavity's boundary. The new tetrahedron
  // of facet (t, f) is t with vertex f replaced by v, which keeps the orientation positive because
  // v sees the facet from t's side. The deleted t's slot for face f is pointed at the new
  // tetrahedron, which is how the rotation recognizes a boundary facet and finds its tetrahedron.
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
  }
  // Pass 2: link the new tetrahedra to each other (which also points each vertex at one).
  if (!linkByEdgeTable())
  {
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

// Every new face is recorded at its directed edge a->b and linked to the face recorded at b->a.
// Edges are indexed by local numbers of the boundary's vertices, given on first sight through
// localNumberSlot() without a branch (a new vertex takes number `count`, which only advances then).
// Returns false, changing nothing, when the boundary has more than kMaxLocalVertices vertices.
bool Inserter::linkByEdgeTable()
{
  const std::vector<TetId>& created = cavity_.created;
  std::vector<std::uint16_t>& local = cavity_.localNumbers;
  std::vector<VertId>& vertexOf = cavity_.localVertex;
  std::vector<TetId>& firstTet = cavity_.localTet;
  local.resize(4 * created.size());
  vertexOf.resize(Cavity::kMaxLocalVertices + 4);
  firstTet.resize(Cavity::kMaxLocalVertices + 4);
  std::uint32_t count = 0;
  bool fits = true;
  for (std::size_t i = 0; i < created.size() && fits; ++i)
  {
    VertId nv[4];
    tets_.vertices(created[i], nv);
    for (int k = 0; k < 4; ++k)
    {
      const VertId u = nv[k];
      TetId& entry = localNumberSlot(u);
      const bool isNew = (entry & kHighHalf) != kLocalTag;
      const auto number = static_cast<std::uint16_t>(isNew ? count : entry);
      entry = kLocalTag | number;
      local[4 * i + k] = number;
      vertexOf[count] = u;
      firstTet[count] = created[i];
      count += isNew;
    }
    fits = count <= Cavity::kMaxLocalVertices;
  }
  // The width of the table is a power of two >= count, so small cavities use a small corner of it.
  std::uint32_t width = 16;
  while (width < count)
    width *= 2;
  if (fits && cavity_.edgeFace.size() < std::size_t(width) * width)
    cavity_.edgeFace.resize(std::size_t(width) * width);
  cavity_.interiorFaces.resize(3 * created.size());
  for (std::size_t i = 0; i < created.size() && fits; ++i)
  {
    const int g = cavity_.boundary[i].face;
    for (int j = 0; j < 3; ++j)
    {
      const InteriorFace& face = kInterior[g][j];
      const std::uint32_t a = local[4 * i + face.a], b = local[4 * i + face.b];
      cavity_.edgeFace[a * width + b] = faceCode(created[i], face.face);
      cavity_.interiorFaces[3 * i + j] = {faceCode(created[i], face.face), b * width + a};
    }
  }
  // Each vertex gets one of its new tetrahedra in place of its number.
  for (std::uint32_t k = 0; k < count; ++k)
    localNumberSlot(vertexOf[k]) = firstTet[k];
  ghostTet_ = kNoTet;
  if (!fits)
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
