// The kernel's built-in check (Options::checkMesh, on in debug builds): every invariant that
// TetMesh.h states, the per-vertex entry points, and the local Delaunay (for weighted points,
// regular) property, decided with the kernel's own exact predicates. The tests' independent oracle
// is Testing/Validation; this check looks inside the mesh, where a broken invariant shows before
// it corrupts an output.
#include "insertion/Triangulator.h"

#include <algorithm>
#include <map>
#include <sstream>

namespace fd3
{
namespace
{
/// Collects violations, keeping the first few of each kind.
class Report
{
public:
  std::ostream& add(const char* kind)
  {
    const int seen = ++count_[kind];
    if (seen <= kShown)
      return text_ << kind << ": ";
    discard_.str("");
    return discard_;
  }
  std::string str() const
  {
    std::ostringstream out;
    out << text_.str();
    for (const auto& [kind, count] : count_)
      if (count > kShown)
        out << kind << ": " << count - kShown << " more\n";
    return out.str();
  }

private:
  static constexpr int kShown = 5;
  std::ostringstream text_, discard_;
  std::map<std::string, int> count_;
};
} // namespace

/// The checks of Triangulator::checkMesh(), one kind at a time.
class MeshCheck
{
public:
  explicit MeshCheck(const Triangulator& triangulator)
    : triangulator_(triangulator), tets_(triangulator.mesh_.tets),
      weights_(triangulator.mesh_.weights), slots_(tets_.slots()),
      predicates_(triangulator.inserters_[0]->predicates()) // a copy: it leaves the counters alone
  {}

  std::string run()
  {
    const std::vector<char> listedFree = freeSlots();
    std::vector<char> isVertex(triangulator_.vertexCount(), 0);
    for (TetId t = 0; t < slots_; ++t)
    {
      if (!tets_.isDead(t))
        tetrahedron(t, isVertex);
      else if (!listedFree[t])
        report_.add("free list") << "dead slot " << t << " is not listed\n";
    }
    vertexEntries(isVertex);
    return report_.str();
  }

private:
  const double* point(VertId v) const { return triangulator_.point(v); }

  /// Every slot that the pools list as free is dead and listed once; which ones are listed.
  std::vector<char> freeSlots()
  {
    std::vector<char> listed(slots_, 0);
    for (const auto& pool : triangulator_.pools_)
      for (TetId t : pool->freeSlots())
      {
        if (t >= slots_ || !tets_.isDead(t))
          report_.add("free list") << "slot " << t << " is listed but live\n";
        else if (listed[t]++)
          report_.add("free list") << "slot " << t << " is listed twice\n";
      }
    return listed;
  }

  void tetrahedron(TetId t, std::vector<char>& isVertex)
  {
    if (tets_.flags(t) != 0)
      report_.add("flags") << "tet " << t << " keeps cavity flags\n";
    VertId tv[4];
    tets_.vertices(t, tv);
    for (int k = 0; k < 4; ++k)
    {
      if (tv[k] == kInfinite && k != 3)
        report_.add("ghost") << "tet " << t << " has the ghost vertex at " << k << "\n";
      else if (tv[k] != kInfinite && tv[k] >= isVertex.size())
        report_.add("vertex") << "tet " << t << " has vertex " << tv[k] << " out of range\n";
      else if (tv[k] != kInfinite)
        isVertex[tv[k]] = 1;
    }
    for (int f = 0; f < 4; ++f)
      adjacency(t, f, tv);
    geometry(t, tv);
  }

  /// The face f of t and its neighbour's point back to each other and have the same vertices.
  void adjacency(TetId t, int f, const VertId tv[4])
  {
    const FaceCode back = tets_.neighbor(t, f);
    if (back == kUnlinked || tetOf(back) >= slots_ || tets_.isDead(tetOf(back)) ||
      tets_.across(back) != faceCode(t, f))
    {
      report_.add("adjacency") << "tet " << t << " face " << f << " is not linked both ways\n";
      return;
    }
    VertId nv[4];
    tets_.vertices(tetOf(back), nv);
    for (int k = 0; k < 4; ++k)
    {
      bool shared = k == f;
      for (int m = 0; m < 4; ++m)
        shared |= m != faceOf(back) && nv[m] == tv[k];
      if (!shared)
        report_.add("adjacency") << "tet " << t << " face " << f
                                 << " differs from its neighbour's\n";
    }
  }

  /// Orientation, hull faces facing out, and (unless a volume threshold was used) every face
  /// locally Delaunay: exactly, with the kernel's predicates.
  void geometry(TetId t, const VertId tv[4])
  {
    if (tets_.isGhost(t))
    {
      // The hull face points outwards: the finite tetrahedron behind it lies on its negative side.
      const FaceCode inside = tets_.neighbor(t, 3);
      const VertId w = tets_.vertex(tetOf(inside), faceOf(inside));
      if (w == kInfinite ||
        predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(w)) >= 0)
        report_.add("ghost") << "tet " << t << " does not face out of the hull\n";
      return;
    }
    if (predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])) <= 0)
      report_.add("orientation") << "tet " << t << " is not positively oriented\n";
    if (triangulator_.mesh_.options.volumeThreshold > 0)
      return;
    for (int f = 0; f < 4; ++f)
    {
      const FaceCode back = tets_.neighbor(t, f);
      const VertId opposite = tets_.vertex(tetOf(back), faceOf(back));
      if (opposite != kInfinite && conflict(tv, opposite) > 0)
        report_.add("Delaunay") << "tet " << t << " face " << f << " is not locally "
                                << (weights_.empty() ? "Delaunay\n" : "regular\n");
    }
  }

  /// insphere, or for weighted points the power test, of u against the tetrahedron tv.
  int conflict(const VertId tv[4], VertId u)
  {
    const double* p[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
    if (weights_.empty())
      return predicates_.inSphere(p[0], p[1], p[2], p[3], point(u));
    const double w[4] = {weights_[tv[0]], weights_[tv[1]], weights_[tv[2]], weights_[tv[3]]};
    return predicates_.powerTest(p, point(u), w, weights_[u]);
  }

  /// Every vertex's entry tetrahedron is live and has it; as many vertices as were inserted.
  void vertexEntries(const std::vector<char>& isVertex)
  {
    std::size_t vertices = 0;
    for (VertId u = 0; u < isVertex.size(); ++u)
    {
      if (!isVertex[u])
        continue;
      ++vertices;
      const TetId t = triangulator_.mesh_.vertices[u].tet;
      VertId tv[4];
      if (t < slots_ && !tets_.isDead(t))
        tets_.vertices(t, tv);
      if (t >= slots_ || tets_.isDead(t) || std::count(tv, tv + 4, u) != 1)
        report_.add("vertex tet") << "vertex " << u << " points to tet " << t
                                  << ", not one of its own\n";
    }
    const std::size_t inserted = triangulator_.statistics().insertedPoints;
    if (vertices != inserted)
      report_.add("vertices") << vertices << " vertices in the mesh, " << inserted << " inserted\n";
  }

  const Triangulator& triangulator_;
  const TetMesh& tets_;
  const std::vector<double>& weights_;
  const std::size_t slots_;
  Predicates predicates_;
  Report report_;
};

std::string Triangulator::checkMesh() const
{
  return MeshCheck(*this).run();
}

} // namespace fd3
