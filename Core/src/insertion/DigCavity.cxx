// Growing the cavity (the paper's core): from a tetrahedron in conflict, through adjacency, every
// tetrahedron whose circumsphere contains the new point (exact insphere, ties broken
// symbolically), or, for weighted points, to whose orthogonal sphere the new point has a negative
// power distance (exact power test). With exact predicates the conflict zone is connected, so
// growing it from any of its tetrahedra finds all of it.
#include "insertion/Inserter.h"

#include <algorithm>
#include <cassert>

namespace fd3
{
namespace
{
// The faces of a tetrahedron other than the one it was entered through, which leads back into
// the cavity: a fixed three faces are visited, not four with a skip whose position is random.
constexpr FaceCode kFacesBesides[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
} // namespace

bool Inserter::isBeyondHullFace(TetId ghost, VertId v)
{
  VertId tv[4];
  tets_.vertices(ghost, tv);
  return predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(v)) > 0;
}

// A ghost's circumsphere is the open half-space beyond its hull face. The rare point on the face's
// plane is a function of its own: written here, its calls' register saves burdened every test.
bool Inserter::ghostInConflict(TetId ghost, VertId v)
{
  VertId tv[4];
  tets_.vertices(ghost, tv);
  const int side = predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(v));
  return side != 0 ? side > 0 : onHullPlaneInConflict(ghost, v);
}

// A point on a hull face's plane takes the verdict of the finite tetrahedron behind the face, so
// that the two never disagree and no flat tetrahedron is created.
bool Inserter::onHullPlaneInConflict(TetId ghost, VertId v)
{
  const TetId behind = tetOf(tets_.neighbor(ghost, 3));
  if (owners_ && !acquire(behind))
  {
    lockLost_ = true; // another inserter's: the insertion is put off
    return false;
  }
  return openConflict(behind, v);
}

// Whether v conflicts with the finite tetrahedron t, ties broken symbolically. Out of line, for the
// tests that the search's first filter leaves open: the search keeps no pointer to the points
// alive for them.
bool Inserter::openConflict(TetId t, VertId v)
{
  VertId tv[4];
  tets_.vertices(t, tv);
  return conflictSoS(tv, v) > 0;
}

void Inserter::undoCavity()
{
  for (const FaceCode c : cavity_.deleted)
    tets_.setFlags(tetOf(c), 0);
  for (const FaceCode b : cavity_.boundary)
    tets_.setFlags(tetOf(tets_.across(b)), 0);
  for (const TetId t : cavity_.rejected)
    tets_.setFlags(t, 0);
}

std::size_t Inserter::makeRoomInCavityLists(std::size_t count)
{
  // The lists keep their memory from one insertion to the next (a ScratchList grows by half at
  // least), and each takes all the room it has.
  cavity_.deleted.resize(std::max(count, cavity_.deleted.capacity()));
  cavity_.boundary.resize(std::max(count, cavity_.boundary.capacity()));
  const std::size_t room = std::min(cavity_.deleted.capacity(), cavity_.boundary.capacity());
  cavity_.deleted.resize(room);
  cavity_.boundary.resize(room);
  return room;
}

// Returns false, undoing everything, when the cavity reaches a tetrahedron that is not the
// inserter's: in a region, one with a vertex outside it (the faces of the tetrahedron at hand are
// still tested, which reads only its neighbours: three vertices in the region, no other inserter
// writes them); in a locking pass, one that another inserter holds (not read at all).
//
// No branch depends on a test's outcome, a coin toss to the predictor: the outcome only picks the
// flag written and which list's end advances (the lists have room for every face of the
// tetrahedron at hand). Behind a mispredicted branch, the processor threw away the next tests it
// had started while the determinant was computed. The records, the vertices and the lists are
// reached through locals, which the compiler keeps in registers across the stores.
template <Inserter::Access A, Inserter::ConflictTest Test>
bool Inserter::digCavity(TetId base, VertId v)
{
  constexpr bool Weighted = Test == ConflictTest::Power;
  const TetRecords tets = tets_.records();
  const Vertex* const vertices = mesh_.vertices.data();
  const auto probe = conflictProbe<Weighted>(v);
  const double* const weights = mesh_.weights.data();
  cavity_.clear();
  // The lists' ends, and the last entry of `deleted` that may be visited before they need more
  // room: pointers, for fewer values to keep in registers across the tests.
  FaceCode* deletedEnd = cavity_.deleted.data();
  FaceCode* boundaryEnd = cavity_.boundary.data();
  const FaceCode* lastWithRoom = nullptr;
  const auto makeRoom = [&](std::size_t count) {
    const std::size_t inCavity = deletedEnd - cavity_.deleted.data();
    const std::size_t facets = boundaryEnd - cavity_.boundary.data();
    const std::size_t room = makeRoomInCavityLists(count);
    deletedEnd = cavity_.deleted.data() + inCavity;
    boundaryEnd = cavity_.boundary.data() + facets;
    // Before the tetrahedron of rank i is visited, each list holds at most 3i + 2 entries (1 + 4
    // for the base, 3 for each one after it).
    lastWithRoom = cavity_.deleted.data() + (room - 5) / 3;
  };
  makeRoom(64);
  bool given = false; // the cavity reached beyond what this inserter may change
  // Face `face` of a tetrahedron in the cavity: the tetrahedron across is tested if it was not
  // yet, and the face is on the boundary unless that one is in the cavity.
  const auto visit = [&](FaceCode face) {
    const FaceCode across = tets.across(face);
    // The tetrahedron across is named by its id only where a rare case needs it (and, in a
    // locking pass, for its owner): kept in a register for them, the id pushed the search's own
    // values to the stack.
    if constexpr (A == Access::Locking)
      if (given || !acquire(tetOf(across)))
      {
        given = true; // another inserter's: not even its flags may be read
        return;
      }
    const TetRecord record = tets.recordOfFace(across);
    const std::uint32_t flag = record.flags();
    if (flag == kInCavity)
      return;
    bool inside = false;
    if (flag == 0)
    {
      VertId nv[4];
      record.vertices(nv);
      if (nv[3] == kInfinite)
      {
        inside = ghostInConflict(tetOf(across), v);
        if constexpr (A == Access::Locking)
          given |= lockLost_;
      }
      else if constexpr (Weighted)
        inside = probe.inside(vertices[nv[0]].xyz, vertices[nv[1]].xyz, vertices[nv[2]].xyz,
          vertices[nv[3]].xyz, weights[nv[0]], weights[nv[1]], weights[nv[2]], weights[nv[3]]);
      else
        inside = probe.template insideFirstFiltered<Test == ConflictTest::InSphereLifts>(
          vertices[nv[0]].xyz, vertices[nv[1]].xyz, vertices[nv[2]].xyz, vertices[nv[3]].xyz,
          [&] { return openConflict(tetOf(across), v); });
      assert(mayTouch(tetOf(across)));
      tets.addFlags(record, inside ? kInCavity : kNotInCavity);
      *deletedEnd = across;
      deletedEnd += inside;
      // The neighbours of every tested tetrahedron, kept ones too: a prefetch chosen by the
      // outcome would wait for the determinant.
      for (int g = 0; g < 4; ++g)
      {
        const FaceCode m = record.neighbor(g);
        tets.prefetchOfFace(m);
        if constexpr (A == Access::Locking)
          prefetch(owners_ + tetOf(m));
      }
      // It shares with the tetrahedron at hand, whose four vertices are in the region, all but
      // the one opposite.
      if constexpr (A == Access::Region)
      {
        const VertId opposite = nv[faceOf(across)];
        given |= inside && opposite != kInfinite && !region_.contains(vertices[opposite].xyz);
      }
    }
    *boundaryEnd = face;
    boundaryEnd += !inside;
  };
  assert(mayTouch(base));
  tets.setFlags(base, kInCavity);
  *deletedEnd++ = faceCode(base, 0);
  for (int f = 0; f < 4; ++f)
    prefetchTet(tetOf(tets.neighbor(base, f)));
  for (int f = 0; f < 4; ++f)
    visit(faceCode(base, f));
  for (const FaceCode* next = cavity_.deleted.data() + 1; next < deletedEnd && !given; ++next)
  {
    if (next > lastWithRoom)
    {
      const std::size_t i = next - cavity_.deleted.data();
      makeRoom(3 * i + 5);
      next = cavity_.deleted.data() + i;
    }
    const FaceCode entered = *next;
    const FaceCode face0 = entered & ~FaceCode(3);
    const FaceCode* faces = kFacesBesides[faceOf(entered)];
    visit(face0 | faces[0]);
    visit(face0 | faces[1]);
    visit(face0 | faces[2]);
  }
  const std::size_t inCavity = deletedEnd - cavity_.deleted.data();
  cavity_.deleted.resize(inCavity);
  cavity_.boundary.resize(boundaryEnd - cavity_.boundary.data());
  if (given)
  {
    lockLost_ = false;
    undoCavity();
    return false;
  }
  stats_.cavityTetrahedra += inCavity;
  return true;
}

template bool Inserter::digCavity<Inserter::Access::Free, Inserter::ConflictTest::InSphereStatic>(
  TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Region, Inserter::ConflictTest::InSphereStatic>(
  TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Locking,
  Inserter::ConflictTest::InSphereStatic>(TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Free, Inserter::ConflictTest::InSphereLifts>(
  TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Region, Inserter::ConflictTest::InSphereLifts>(
  TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Locking, Inserter::ConflictTest::InSphereLifts>(
  TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Free, Inserter::ConflictTest::Power>(
  TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Region, Inserter::ConflictTest::Power>(
  TetId, VertId);
template bool Inserter::digCavity<Inserter::Access::Locking, Inserter::ConflictTest::Power>(
  TetId, VertId);

} // namespace fd3
