// The scratch of one insertion, in a type of its own: the cavity (the paper's core) and its
// boundary, the new tetrahedra, and the table that links them. It is reused from one insertion
// to the next, so that the steady state allocates nothing.
#ifndef fd3_Cavity_h
#define fd3_Cavity_h

#include "TetMesh.h"
#include "system/ScratchList.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace fd3
{

/// What holds a vertex's local number during a fill (its Vertex::tet, or an entry of LocalNumbers)
/// before it has one: any value below 2^31 does, as a tetrahedron id.
constexpr TetId kUnnumbered = 0;

/// The fill's local numbers of the boundary's vertices where their Vertex::tet may not hold them:
/// in a locking pass, a vertex can be on the boundaries of two threads' cavities at once. Open
/// addressing, sized for the boundary at hand and cleared for each fill.
class LocalNumbers
{
public:
  /// Empty, with room for `count` vertices.
  void reset(std::size_t count)
  {
    std::size_t size = 16;
    shift_ = 28;
    for (; size < 2 * count; size *= 2)
      --shift_;
    keys_.assign(size, kNoVertex);
    values_.resize(size);
    mask_ = size - 1;
  }
  /// The entry of u, kUnnumbered when new.
  TetId& slot(VertId u)
  {
    std::size_t i = static_cast<std::uint32_t>(u * 0x9E3779B1u) >> shift_; // Fibonacci hashing
    while (keys_[i] != u && keys_[i] != kNoVertex)
      i = (i + 1) & mask_;
    if (keys_[i] == kNoVertex)
    {
      keys_[i] = u;
      values_[i] = kUnnumbered;
    }
    return values_[i];
  }

private:
  std::vector<VertId> keys_;
  std::vector<TetId> values_;
  std::size_t mask_ = 0;
  int shift_ = 28;
};

struct Cavity
{
  /// In conflict with the new point: flagged kInCavity, to delete. Each as the face by which the
  /// search entered it (the base by face 0): tetOf() names the tetrahedron.
  ScratchList<FaceCode> deleted;
  /// Flagged kNotInCavity, to clear when the insertion ends: given back by the correction, or
  /// across a boundary facet that the correction took away. Those tested and kept that are across
  /// the final boundary are cleared through it, unlisted.
  ScratchList<TetId> rejected;
  /// The faces of the deleted tetrahedra across which the kept ones lie, each as its face code
  /// (tetOf(): the deleted tetrahedron, faceOf(): the face).
  ScratchList<FaceCode> boundary;
  ScratchList<TetId> created; ///< created[i] is the new tetrahedron on boundary[i]

  // The edge table of FillCavity.cxx. The new tetrahedra's vertices get local numbers
  // 0..count-1 (kept in their Vertex::tet during the fill); edgeFace[a * width + b] is the new
  // face on the directed boundary edge a->b, width being a power of two >= count, known from the
  // number of facets. Every entry read was written in the same insertion, so the table is never
  // cleared.
  static constexpr std::uint32_t kMaxLocalVertices = 512;
  struct LocalVertex
  {
    VertId vertex;
    TetId tet; ///< one of its new tetrahedra
  };
  /// The three faces that new tetrahedron i shares with others, those on the edges of its
  /// boundary facet: for each edge j (q_j -> q_j+1 of the facet's vertices), the entry of edgeFace
  /// that holds its neighbour.
  struct InteriorFaces
  {
    std::uint32_t reversedEdge[3];
  };
  ScratchList<LocalVertex> localVertices;   ///< by local number
  ScratchList<FaceCode> edgeFace;           ///< grown on demand, up to kMaxLocalVertices^2
  ScratchList<InteriorFaces> interiorFaces; ///< by new tetrahedron
  LocalNumbers localNumbers;                ///< in a locking pass, in place of Vertex::tet

  void clear()
  {
    deleted.clear();
    rejected.clear();
    boundary.clear();
    created.clear();
  }
  /// Gives the memory back (the kernel's output phase needs it more).
  void release() { *this = Cavity(); }
};

} // namespace fd3

#endif
