// The tetrahedral mesh as flat arrays (structure of arrays), 33 bytes per tetrahedron:
//   vertices[4*t + i]  vertex i of tetrahedron t (vertex ids are insertion ranks);
//   neighbors[4*t + f] = 4*t' + f': t' shares the face of t opposite vertex f, and f' is the vertex
//                      of t' opposite that face (the paper's adjacency table, in O(1) both ways);
//   flags[t]           cavity bookkeeping and the free-slot mark.
// Invariants (checked by Triangulator::checkMesh in debug builds):
//   * every live tetrahedron is positively oriented (VTK convention);
//   * the convex hull is closed by ghost tetrahedra whose vertex 3 is kInfinite, oriented as if
//     kInfinite were a point far beyond their hull face;
//   * neighbors[neighbors[4t+f]] == 4t+f for every live t and face f;
//   * freed slots hold kDeadVertex in vertex 0 and are listed in freeSlots.
#ifndef fd3_TetMesh_h
#define fd3_TetMesh_h

#include <cassert>
#include <cstdint>
#include <vector>

namespace fd3
{

using TetId = std::uint32_t;
using VertId = std::uint32_t;
using FaceCode = std::uint32_t; // 4*tet + face

constexpr VertId kInfinite = 0xFFFFFFFFu;
constexpr VertId kDeadVertex = 0xFFFFFFFEu;
constexpr FaceCode kUnlinked = 0xFFFFFFFFu;

inline TetId tetOf(FaceCode code)
{
  return code >> 2;
}
inline int faceOf(FaceCode code)
{
  return static_cast<int>(code & 3u);
}
inline FaceCode faceCode(TetId t, int f)
{
  return (t << 2) | static_cast<FaceCode>(f);
}

enum TetFlag : std::uint8_t
{
  kInCavity = 1,   // in the conflict zone of the point being inserted
  kNotInCavity = 2 // tested during this insertion and kept
};

struct TetMesh
{
  std::vector<VertId> vertices;
  std::vector<FaceCode> neighbors;
  std::vector<std::uint8_t> flags;
  std::vector<TetId> freeSlots;

  std::size_t slots() const { return flags.size(); }
  bool isGhost(TetId t) const { return vertices[4 * t + 3] == kInfinite; }
  bool isDead(TetId t) const { return vertices[4 * t] == kDeadVertex; }
  FaceCode neighbor(TetId t, int f) const { return neighbors[4 * t + f]; }

  void link(FaceCode a, FaceCode b)
  {
    neighbors[a] = b;
    neighbors[b] = a;
  }

  /// A slot for a new tetrahedron: a freed one first (the paper's memory management), else a new one.
  TetId allocate()
  {
    if (!freeSlots.empty())
    {
      const TetId t = freeSlots.back();
      freeSlots.pop_back();
      return t;
    }
    const TetId t = static_cast<TetId>(flags.size());
    vertices.resize(vertices.size() + 4);
    neighbors.resize(neighbors.size() + 4);
    flags.push_back(0);
    return t;
  }

  void release(TetId t)
  {
    vertices[4 * t] = kDeadVertex;
    flags[t] = 0;
    freeSlots.push_back(t);
  }

  void reserve(std::size_t tets)
  {
    vertices.reserve(4 * tets);
    neighbors.reserve(4 * tets);
    flags.reserve(tets);
  }
};

} // namespace fd3

#endif
