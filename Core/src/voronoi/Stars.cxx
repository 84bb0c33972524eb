// The stars of the vertices (steps 2 and 3 of VoronoiCells.cxx): each tetrahedron's vertices
// in ascending order (orientation kept), the tetrahedra grouped by their lowest vertex, each
// group ordered by the other three, then each vertex's other tetrahedra listed: an order that
// the points alone decide, whatever the threads.
#include "voronoi/Stars.h"

#include <algorithm>
#include <array>

namespace fd3::voronoi
{
namespace
{
/// Whether tetrahedron a's other three vertices come before b's, lexicographically.
bool otherVerticesLess(const std::uint32_t* a, const std::uint32_t* b)
{
  return a[1] != b[1] ? a[1] < b[1] : (a[2] != b[2] ? a[2] < b[2] : a[3] < b[3]);
}

/// Sorts a group's tetrahedra by their other three vertices: by insertion where it is small, as
/// nearly every group is, else through an index.
void sortGroup(std::uint32_t* first, std::size_t size, std::vector<std::uint32_t>& scratch)
{
  using Tet = std::array<std::uint32_t, 4>;
  constexpr std::size_t kInsertion = 32;
  if (size <= kInsertion)
  {
    for (std::size_t i = 1; i < size; ++i)
    {
      Tet moving;
      std::copy_n(first + 4 * i, 4, moving.begin());
      std::size_t j = i;
      for (; j > 0 && otherVerticesLess(moving.data(), first + 4 * (j - 1)); --j)
        std::copy_n(first + 4 * (j - 1), 4, first + 4 * j);
      std::copy_n(moving.begin(), 4, first + 4 * j);
    }
    return;
  }
  std::vector<Tet> tets(size);
  for (std::size_t i = 0; i < size; ++i)
    std::copy_n(first + 4 * i, 4, tets[i].begin());
  std::sort(tets.begin(), tets.end(),
    [](const Tet& a, const Tet& b) { return otherVerticesLess(a.data(), b.data()); });
  scratch.assign(&tets[0][0], &tets[0][0] + 4 * size);
  std::copy(scratch.begin(), scratch.end(), first);
}
} // namespace

void sortVertices(ThreadTeam& team, Triangulation& mesh)
{
  std::uint32_t* t4 = mesh.tetrahedra.data();
  team.forRanges(mesh.numberOfTetrahedra(), "voronoi vertex order",
    [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
      {
        std::uint32_t* v = t4 + 4 * t;
        // A sorting network of five exchanges; each exchange flips the orientation.
        // Without branches: each exchange is a coin toss.
        bool odd = false;
        auto exchange = [&](int i, int j) {
          const std::uint32_t a = v[i], b = v[j];
          const bool swap = b < a;
          v[i] = swap ? b : a;
          v[j] = swap ? a : b;
          odd ^= swap;
        };
        exchange(0, 1);
        exchange(2, 3);
        exchange(0, 2);
        exchange(1, 3);
        exchange(1, 2);
        const std::uint32_t third = v[2], fourth = v[3];
        v[2] = odd ? fourth : third;
        v[3] = odd ? third : fourth;
      }
    });
}

void groupByLowestVertex(
  ThreadTeam& team, Triangulation& mesh, std::size_t vertices, std::size_t owners, Stars& stars)
{
  const std::size_t tets = mesh.numberOfTetrahedra();
  const std::uint32_t* t4 = mesh.tetrahedra.data();
  stars.ownStart.resize(vertices + 1);
  stars.otherStart.resize(vertices + 1);
  stars.ownStart[0] = stars.otherStart[0] = 0;
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::fill(&stars.ownStart[lo + 1], &stars.ownStart[hi] + 1, 0);
    std::fill(&stars.otherStart[lo + 1], &stars.otherStart[hi] + 1, 0);
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      if (v[0] >= owners)
        continue;
      // Branches, not sums of flags: a thread must not write another's entries, even unchanged.
      if (v[0] >= lo && v[0] < hi)
        ++stars.ownStart[v[0] + 1];
      for (int k = 1; k < 4; ++k)
        if (v[k] >= lo && v[k] < hi)
          ++stars.otherStart[v[k] + 1];
    }
  });
  team.accumulate(stars.ownStart, "voronoi stars");
  team.accumulate(stars.otherStart, "voronoi stars");
  stars.tetrahedra.resize(4 * std::size_t(stars.ownStart[vertices]));
  VoronoiCells::Offsets next(vertices); // where each group's next tetrahedron goes
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::copy(&stars.ownStart[lo], &stars.ownStart[hi], &next[lo]);
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      if (v[0] >= lo && v[0] < hi && v[0] < owners)
        std::copy_n(v, 4, stars.tetrahedra.data() + 4 * next[v[0]]++);
    }
  });
  // The mesh's array (4 entries a tetrahedron) is the room for the others' list (3 a
  // tetrahedron), in pages already the process's.
  stars.others.swap(mesh.tetrahedra);
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::vector<std::uint32_t> scratch;
    for (std::size_t v = lo; v < hi; ++v)
      sortGroup(stars.tetrahedra.data() + 4 * stars.ownStart[v],
        stars.ownStart[v + 1] - stars.ownStart[v], scratch);
  });
}

void listOthers(ThreadTeam& team, const Flags& inBox, Stars& stars)
{
  const std::size_t tets = inBox.size(), vertices = stars.ownStart.size() - 1;
  const std::uint32_t* t4 = stars.tetrahedra.data();
  stars.others.resize(stars.otherStart[vertices]);
  stars.clipped.resize(vertices);
  VoronoiCells::Offsets next(vertices); // where each vertex's next other tetrahedron goes
  team.forRanges(vertices, "voronoi stars", [&](std::size_t, std::size_t lo, std::size_t hi) {
    std::copy(&stars.otherStart[lo], &stars.otherStart[hi], &next[lo]);
    std::fill(&stars.clipped[lo], &stars.clipped[hi], 0);
    for (std::size_t t = 0; t < tets; ++t)
    {
      const std::uint32_t* v = t4 + 4 * t;
      if (v[0] >= lo && v[0] < hi)
        stars.clipped[v[0]] |= !inBox[t];
      for (int k = 1; k < 4; ++k)
        if (v[k] >= lo && v[k] < hi)
        {
          stars.others[next[v[k]]++] = static_cast<std::uint32_t>(t);
          stars.clipped[v[k]] |= !inBox[t];
        }
    }
  });
}

} // namespace fd3::voronoi
