// The tetrahedral mesh: one 32-byte record per tetrahedron in a flat array, so that visiting a
// tetrahedron (its flags, vertices and neighbours) costs one cache line:
//   record t = [v0 v1 v2 v3 | n0 n1 n2 n3]
//   v_i  vertex i: a VertId, the vertex's insertion rank, which indexes the kernel's own
//        (normalized, reordered) points; the output maps ranks back to input ids. v0's top two
//        bits hold the flags below;
//   n_f  = 4*t' + f': t' shares the face of t opposite vertex f, and f' is the vertex of t'
//        opposite that face (the paper's adjacency table, navigable in O(1) both ways).
// Invariants (checked by Triangulator::checkMesh):
//   * every live tetrahedron is positively oriented (VTK convention);
//   * the convex hull is closed by ghost tetrahedra whose vertex 3 is kInfinite, oriented as if
//     kInfinite were a point far beyond their hull face;
//   * neighbor(neighbor(c)) == c for every face code c of a live tetrahedron, and the two faces
//     carry the same three vertices;
//   * freed slots are flagged kDead and listed once in the free list; every other slot is live;
//     flags are 0 between insertions.
#ifndef fd3_TetMesh_h
#define fd3_TetMesh_h

#include "Platform.h"

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace fd3
{

using TetId = std::uint32_t;
using VertId = std::uint32_t;
using FaceCode = std::uint32_t; // 4*tet + face

constexpr VertId kInfinite = 0xFFFFFFFFu; // the ghost vertex, at infinity
constexpr VertId kNoVertex = 0xFFFFFFFEu; // "none found"
constexpr FaceCode kUnlinked = 0xFFFFFFFFu;
constexpr int kVertexIdBits = 30;
constexpr std::uint32_t kMaxVertices = 1u << kVertexIdBits;
constexpr std::size_t kMaxTetrahedra = std::size_t(1) << 30;

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

/// The vertices of face f of a tetrahedron (the face opposite vertex f), ordered so that its normal
/// (right-hand rule) points out of the tetrahedron: (face, f) is an odd permutation of (0, 1, 2, 3).
constexpr int kFaceVertices[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

enum TetFlag : std::uint32_t
{
  kInCavity = 1,    // in the conflict zone of the point being inserted
  kNotInCavity = 2, // tested during this insertion and kept
  kDead = 3         // a free slot
};

class TetMesh
{
public:
  std::size_t slots() const { return records_.size() / 8; }

  VertId vertex(TetId t, int i) const
  {
    const std::uint32_t v = records_[8 * std::size_t(t) + i];
    return i == 0 ? v & kIdMask : v;
  }
  /// The four vertices of t (v0 without its flags).
  void vertices(TetId t, VertId out[4]) const
  {
    const std::uint32_t* r = &records_[8 * std::size_t(t)];
    out[0] = r[0] & kIdMask;
    out[1] = r[1];
    out[2] = r[2];
    out[3] = r[3];
  }

  FaceCode neighbor(TetId t, int f) const { return records_[8 * std::size_t(t) + 4 + f]; }
  FaceCode across(FaceCode code) const { return neighbor(tetOf(code), faceOf(code)); }
  void setNeighbor(FaceCode code, FaceCode value)
  {
    records_[8 * std::size_t(tetOf(code)) + 4 + faceOf(code)] = value;
  }
  void link(FaceCode a, FaceCode b)
  {
    setNeighbor(a, b);
    setNeighbor(b, a);
  }

  std::uint32_t flags(TetId t) const { return records_[8 * std::size_t(t)] >> kVertexIdBits; }
  void setFlags(TetId t, std::uint32_t flags)
  {
    std::uint32_t& slot = records_[8 * std::size_t(t)];
    slot = (slot & kIdMask) | (flags << kVertexIdBits);
  }

  /// Starts loading t's record, which the caller will need soon (hides memory latency while
  /// the cavity is grown breadth-first).
  void prefetch(TetId t) const { fd3::prefetch(&records_[8 * std::size_t(t)]); }

  bool isGhost(TetId t) const { return records_[8 * std::size_t(t) + 3] == kInfinite; }
  bool isDead(TetId t) const { return flags(t) == kDead; }

  /// A slot for a new tetrahedron, to be filled by create(): a freed one first (the paper's memory
  /// management: deleted slots are taken by the next tetrahedra created), else a new one.
  TetId allocate()
  {
    TetId t;
    if (!freeSlots_.empty())
    {
      t = freeSlots_.back();
      freeSlots_.pop_back();
    }
    else
    {
      // Face codes 4t+f are 32-bit: beyond 2^30 slots (about 150M points) they would wrap.
      if (slots() >= kMaxTetrahedra)
        throw std::length_error("fd3: more than 2^30 tetrahedra, beyond 32-bit face codes");
      t = static_cast<TetId>(slots());
      // Past the reserved capacity, grow by a quarter rather than std::vector's doubling: the
      // copy then peaks at 2.25 times the records, not 3 times.
      if (records_.size() == records_.capacity())
        records_.reserve(records_.capacity() + records_.capacity() / 4 + 8);
      records_.resize(records_.size() + 8);
    }
    return t;
  }

  /// Writes the whole record of t at once: vertices v (flags clear), no neighbours yet.
  void create(TetId t, const VertId v[4])
  {
    std::uint32_t* r = &records_[8 * std::size_t(t)];
    for (int i = 0; i < 4; ++i)
    {
      r[i] = v[i];
      r[4 + i] = kUnlinked;
    }
  }

  void release(TetId t)
  {
    setFlags(t, kDead);
    freeSlots_.push_back(t);
  }

  void reserve(std::size_t tets) { records_.reserve(8 * tets); }
  /// Slots in use: live tetrahedra, ghosts included.
  std::size_t liveSlots() const { return slots() - freeSlots_.size(); }
  std::size_t capacity() const { return records_.capacity() / 8; }
  const std::vector<TetId>& freeSlots() const { return freeSlots_; }

  /// Hands the records over (for in-place output conversion); the mesh is empty afterwards.
  /// Record t occupies words 8t..8t+7, v0 carrying the flags in its top bits.
  std::vector<std::uint32_t> takeRecords()
  {
    freeSlots_.clear();
    return std::move(records_);
  }

private:
  static constexpr std::uint32_t kIdMask = kMaxVertices - 1;
  std::vector<std::uint32_t> records_;
  std::vector<TetId> freeSlots_;
};

} // namespace fd3

#endif
