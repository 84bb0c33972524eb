// The kernel's built-in check (Options::checkMesh, on in debug builds): every invariant that
// TetMesh.h states, the per-vertex entry points, and the local Delaunay property, decided with the
// kernel's own exact predicates. The tests' independent oracle is Testing/Validation; this check
// looks inside the mesh, where a broken invariant shows before it corrupts an output.
#include "Triangulator.h"

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

std::string Triangulator::checkMesh() const
{
  Predicates predicates = inserters_[0]->predicates(); // a copy: it leaves the counters alone
  const TetMesh& tets = mesh_.tets;
  Report report;
  const std::size_t slots = tets.slots();
  std::vector<char> listedFree(slots, 0);
  for (const auto& pool : pools_)
    for (TetId t : pool->freeSlots())
    {
      if (t >= slots || !tets.isDead(t))
        report.add("free list") << "slot " << t << " is listed but live\n";
      else if (listedFree[t]++)
        report.add("free list") << "slot " << t << " is listed twice\n";
    }
  std::vector<char> isVertex(vertexCount(), 0);
  for (TetId t = 0; t < slots; ++t)
  {
    if (tets.isDead(t))
    {
      if (!listedFree[t])
        report.add("free list") << "dead slot " << t << " is not listed\n";
      continue;
    }
    if (tets.flags(t) != 0)
      report.add("flags") << "tet " << t << " keeps cavity flags\n";
    VertId tv[4];
    tets.vertices(t, tv);
    for (int k = 0; k < 4; ++k)
    {
      if (tv[k] == kInfinite && k != 3)
        report.add("ghost") << "tet " << t << " has the ghost vertex at " << k << "\n";
      else if (tv[k] != kInfinite && tv[k] >= vertexCount())
        report.add("vertex") << "tet " << t << " has vertex " << tv[k] << " out of range\n";
      else if (tv[k] != kInfinite)
        isVertex[tv[k]] = 1;
    }
    for (int f = 0; f < 4; ++f)
    {
      const FaceCode back = tets.neighbor(t, f);
      if (back == kUnlinked || tetOf(back) >= slots || tets.isDead(tetOf(back)) ||
        tets.across(back) != faceCode(t, f))
      {
        report.add("adjacency") << "tet " << t << " face " << f << " is not linked both ways\n";
        continue;
      }
      VertId nv[4];
      tets.vertices(tetOf(back), nv);
      for (int k = 0; k < 4; ++k)
      {
        bool shared = k == f;
        for (int m = 0; m < 4; ++m)
          shared |= m != faceOf(back) && nv[m] == tv[k];
        if (!shared)
          report.add("adjacency") << "tet " << t << " face " << f
                                  << " differs from its neighbour's\n";
      }
    }
    if (tets.isGhost(t))
    {
      // The hull face points outwards: the finite tetrahedron behind it lies on its negative side.
      const FaceCode inside = tets.neighbor(t, 3);
      const VertId w = tets.vertex(tetOf(inside), faceOf(inside));
      if (w == kInfinite ||
        predicates.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(w)) >= 0)
        report.add("ghost") << "tet " << t << " does not face out of the hull\n";
      continue;
    }
    if (predicates.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])) <= 0)
      report.add("orientation") << "tet " << t << " is not positively oriented\n";
    if (mesh_.options.volumeThreshold > 0)
      continue;
    for (int f = 0; f < 4; ++f)
    {
      const FaceCode back = tets.neighbor(t, f);
      const VertId opposite = tets.vertex(tetOf(back), faceOf(back));
      if (opposite != kInfinite &&
        predicates.inSphere(
          point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3]), point(opposite)) > 0)
        report.add("Delaunay") << "tet " << t << " face " << f << " is not locally Delaunay\n";
    }
  }
  std::size_t vertices = 0;
  for (VertId u = 0; u < vertexCount(); ++u)
  {
    if (!isVertex[u])
      continue;
    ++vertices;
    const TetId t = mesh_.vertices[u].tet;
    VertId tv[4];
    if (t < slots && !tets.isDead(t))
      tets.vertices(t, tv);
    if (t >= slots || tets.isDead(t) || std::count(tv, tv + 4, u) != 1)
      report.add("vertex tet") << "vertex " << u << " points to tet " << t
                               << ", not one of its own\n";
  }
  if (vertices != statistics().insertedPoints)
    report.add("vertices") << vertices << " vertices in the mesh, " << statistics().insertedPoints
                           << " inserted\n";
  return report.str();
}

} // namespace fd3
