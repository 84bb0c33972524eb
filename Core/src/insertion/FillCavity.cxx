// Filling the cavity: one new tetrahedron per boundary facet, joining the facet to the new point,
// linked to its neighbours without any search over the mesh. The neighbour across a new face
// (p, u, w) is the other new tetrahedron on the boundary edge uw: found in a table of the
// boundary's directed edges (the paper's one-to-one correspondence of section 3.3 between new
// tetrahedra and boundary facets), or, for cavities with more boundary vertices than the table
// takes, by rotating about uw through the deleted tetrahedra as the paper does. The table grows
// with the cavity: surface samples make cavities of hundreds of tetrahedra, and rotating about
// their long edges cost more than the rest of the insertion.
#include "insertion/Inserter.h"

#include <algorithm>
#include <cassert>
#include <type_traits>

namespace fd3
{
namespace
{
// During a fill, the tet field of each boundary vertex holds kLocalTag | its local number. A
// boundary vertex is a live one, whose field holds a tetrahedron id, below 2^30 (the ghost vertex's
// stand-in and a locking pass's table: kUnnumbered), so the top bit alone tells a number.
constexpr TetId kLocalTag = 0x80000000u;
static_assert(kUnnumbered < kLocalTag && kMaxTetrahedra <= kLocalTag, "untagged");
} // namespace

// Returns false, undoing everything, when the mesh has no room left for the new tetrahedra.
template <Inserter::Access A>
bool Inserter::fillCavity(VertId v)
{
  ScratchList<TetId>& created = cavity_.created;
  created.resize(cavity_.boundary.size());
  if (!pool_.take(tets_, created.size(), created.data()))
  {
    undoCavity();
    return false;
  }
  if constexpr (A == Access::Locking)
    for (const TetId t : created) // this pool's free slots, or new ones no one else can reach
    {
      owners_[t].store(me_, std::memory_order_relaxed);
      held_.push_back(t);
    }
  if (!createAndLink<A>(v))
    linkByRotation();
  assert(std::all_of(cavity_.deleted.begin(), cavity_.deleted.end(),
    [&](FaceCode c) { return isOwned(tetOf(c)) && tets_.isDead(tetOf(c)); }));
  pool_.give(cavity_.deleted);
  const TetRecords tets = tets_.records();
  for (TetId t : cavity_.rejected)
  {
    assert(mayTouch(t));
    tets.setFlags(t, 0);
  }
  regionStart_ = created.back();
  return true;
}

// Three loops. The first creates the new tetrahedron of each boundary facet (t, f): t with vertex f
// replaced by v, which keeps the orientation positive because v sees the facet from t's side,
// linked to the tetrahedron across the facet, whose flags it clears (kNotInCavity: tested and
// kept). The second numbers the facets' vertices and records their edges, the third links the new
// tetrahedra to each other; apart, the first two keep their values in registers, which the compiler
// spilled from one loop doing both. Every facet, in its outward order q0 q1 q2 (kFaceVertices[f]),
// runs along its edges q0->q1, q1->q2, q2->q0, and the facet across each edge runs along it the
// other way: the new face through v and edge qj->qk (opposite the facet's third vertex) is recorded
// at that directed edge and, once every facet is done, linked to the face recorded at qk->qj. Edges
// are indexed by local numbers of the boundary's vertices, given on first sight through
// localNumberSlot() without a branch (a new vertex takes number `count`, which only advances then).
// The boundary is a triangulated sphere, so its vertices number F/2 + 2 for F facets (Euler), which
// sizes the table before the loops. Returns false, with every new tetrahedron created and linked
// across the boundary but not to each other, when the boundary is too large for the table or not a
// sphere after all.
template <Inserter::Access A>
bool Inserter::createAndLink(VertId v)
{
  const TetRecords tets = tets_.records();
  Vertex* const vertices = mesh_.vertices.data();
  const std::size_t facets = cavity_.created.size();
  const std::uint32_t expected = static_cast<std::uint32_t>(facets / 2 + 2);
  std::uint32_t width = 16;
  while (width < expected)
    width *= 2;
  const bool fits = expected <= Cavity::kMaxLocalVertices;
  if (fits && cavity_.edgeFace.size() < std::size_t(width) * width)
    cavity_.edgeFace.resize(std::size_t(width) * width);
  cavity_.localVertices.resize(width + 3);
  if constexpr (A == Access::Locking)
    cavity_.localNumbers.reset(width + 3);
  cavity_.interiorFaces.resize(facets);
  const FaceCode* boundary = cavity_.boundary.data();
  const TetId* created = cavity_.created.data();
  Cavity::LocalVertex* localVertices = cavity_.localVertices.data();
  FaceCode* edgeFace = cavity_.edgeFace.data();
  Cavity::InteriorFaces* interiorFaces = cavity_.interiorFaces.data();
  for (std::size_t i = 0; i < facets; ++i)
  {
    const TetRecord inner = tets.recordOfFace(boundary[i]);
    const int face = faceOf(boundary[i]);
    const FaceCode outer = inner.neighbor(face);
    const TetId n = created[i];
    const TetRecord record = tets.createReplacing(n, inner, face, v);
    assert(mayTouch(n) && mayTouch(tetOf(outer)));
    tets.setNeighbor(record, face, outer);
    tets.setNeighbor(outer, faceCode(n, face));
    tets.setFlags(tets.recordOfFace(outer), 0); // tested and kept
  }
  std::uint32_t count = 0;
  bool linked = fits;
  TetId start = created[0]; // the new point's tetrahedron
  for (std::size_t i = 0; linked && i < facets; ++i)
  {
    const int face = faceOf(boundary[i]);
    const TetId n = created[i];
    VertId u[3];
    tets.faceVertices(n, face, u);
    std::uint32_t local[3];
    const auto number = [&](auto mayBeGhost) {
      for (int j = 0; j < 3; ++j)
      {
        assert(inRegion(u[j]));
        TetId& entry = localNumberSlot<A, decltype(mayBeGhost)::value>(vertices, u[j]);
        const bool isNew = entry < kLocalTag;
        local[j] = isNew ? count : (entry & 0xFFFFu);
        entry = kLocalTag | local[j];
        localVertices[count] = {u[j], n};
        count += isNew;
      }
    };
    // Only a ghost's facet holds the ghost vertex: the others are numbered without a test for it
    // (in a locking pass, the cavity's table takes any vertex).
    const bool ghost = tets.isGhost(n);
    if (ghost && A != Access::Locking)
      number(std::true_type());
    else
      number(std::false_type());
    if (count > width)
    {
      linked = false; // not a sphere after all: the numbers would leave the table
      break;
    }
    if (ghost)
    {
      // On the hull, a walk's start had better be a ghost: where points come from outside the
      // hull (a convex surface's samples), the first test then finds the next one in conflict.
      for (int j = 0; j < 3; ++j)
        localVertices[local[j]].tet = n;
      start = n;
    }
    const int* q = kFaceVertices[face];
    for (int j = 0; j < 3; ++j)
    {
      const std::uint32_t from = local[j], to = local[j == 2 ? 0 : j + 1];
      const FaceCode interior = faceCode(n, q[j == 0 ? 2 : j - 1]);
      edgeFace[from * width + to] = interior;
      interiorFaces[i].reversedEdge[j] = to * width + from;
    }
  }
  // Each vertex gets one of its new tetrahedra in place of its number.
  for (std::uint32_t k = 0; k < count; ++k)
    setVertexTet<A>(localVertices[k].vertex, localVertices[k].tet);
  setVertexTet<A>(v, start);
  ghostTet_ = kUnnumbered;
  if (!linked)
    return false;
  for (std::size_t i = 0; i < facets; ++i)
  {
    const int* q = kFaceVertices[faceOf(boundary[i])];
    const TetRecord n = tets.record(created[i]);
    for (int j = 0; j < 3; ++j)
      tets.setNeighbor(n, q[j == 0 ? 2 : j - 1], edgeFace[interiorFaces[i].reversedEdge[j]]);
  }
  return true;
}

template bool Inserter::fillCavity<Inserter::Access::Free>(VertId);
template bool Inserter::fillCavity<Inserter::Access::Region>(VertId);
template bool Inserter::fillCavity<Inserter::Access::Locking>(VertId);

// createAndLink()'s fallback, for cavities whose boundary the edge table does not take: the
// new tetrahedra exist and are linked across the boundary; each face between two of them is
// linked by rotating about its boundary edge through the deleted tetrahedra, whose slot for each
// boundary facet is first pointed at the new tetrahedron on it (how the rotation recognizes a
// boundary facet). The new tetrahedra's other faces are first marked unlinked: createAndLink()
// leaves them as their slots held them.
void Inserter::linkByRotation()
{
  const ScratchList<TetId>& created = cavity_.created;
  for (std::size_t i = 0; i < created.size(); ++i)
  {
    const FaceCode b = cavity_.boundary[i];
    tets_.setNeighbor(b, faceCode(created[i], faceOf(b)));
    for (int f = 0; f < 4; ++f)
      if (f != faceOf(b))
        tets_.setNeighbor(faceCode(created[i], f), kUnlinked);
  }
  for (std::size_t i = 0; i < created.size(); ++i)
  {
    VertId nv[4];
    tets_.vertices(created[i], nv);
    for (int k = 0; k < 4; ++k)
      setVertexTet(nv[k], created[i]);
    for (int f = 0; f < 4; ++f)
      if (f != faceOf(cavity_.boundary[i]) && tets_.neighbor(created[i], f) == kUnlinked)
        linkAroundEdge(i, f);
  }
}

// New tetrahedron i was built on boundary facet (t, g); its face `face` holds the new point and
// the facet's edge uw. Turn about uw through the deleted tetrahedra, starting with t's other face
// on uw, until a boundary facet is met: the new tetrahedron built on it is the neighbour.
void Inserter::linkAroundEdge(std::size_t i, int face)
{
  const FaceCode facet = cavity_.boundary[i];
  // Local indices of u and w (the same in t and in its new tetrahedron): the two of 0..3 that are
  // neither `face` nor faceOf(facet), as the two bit positions left in a 4-bit mask.
  const unsigned rest = 15u & ~(1u << face) & ~(1u << faceOf(facet));
  int iu = countTrailingZeros(rest);
  int iw = countTrailingZeros(rest & (rest - 1));
  const VertId u = tets_.vertex(tetOf(facet), iu);
  const VertId w = tets_.vertex(tetOf(facet), iw);

  TetId t = tetOf(facet);
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
