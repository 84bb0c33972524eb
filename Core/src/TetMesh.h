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
//   * below slots(), freed slots are flagged kDead and listed once in one pool's free list; every
//     other slot is live; flags are 0 between insertions.
// Threads (the whole kernel's contract; debug builds assert it at every write, Inserter::mayTouch):
//   * outside a parallel pass one thread, the caller's, reads and writes everything;
//   * in a region pass, inserter k runs on its own thread in region R_k (Region, Inserter.h), and
//     reads and writes only the records of tetrahedra with three vertices or more in R_k (the
//     ghost vertex is in every region). No tetrahedron has three vertices in each of two regions,
//     so no record is touched by two threads; a cavity that would reach a tetrahedron with a
//     vertex outside R_k is given up (the point is put off) before anything is written.
//     Vertex::tet (and the fill's local numbers in it) of a vertex in R_k: written by inserter k
//     only; the new point's own record likewise;
//   * in a locking pass, inserter k reads or writes a record only while it holds the tetrahedron
//     in the pass's owner table (OwnerTable, Inserter.h: taken by compare-and-swap, let go with a
//     release store, so the next holder sees every write); slots it frees stay its own, for its
//     pool. Vertex::tet may be written and read by several threads at once (relaxed atomics): it
//     is always some slot, possibly one since freed, which a walk takes and checks before it
//     reads it; the fill's local numbers go to a table of the inserter's own;
//   * new slots come from the inserter's own SlotPool; the mesh hands out blocks through an atomic
//     counter (claim()); makeRoom() and reserve() move the records and run between passes only;
//   * the background grid's cells are relaxed atomics holding hints: any thread reads and writes
//     them, and a stale hint only lengthens a walk (BackgroundGrid.h);
//   * predicates, statistics, scratch and the cavity are per inserter; progress is reported and
//     abort checked by the caller's thread alone (Triangulator).
#ifndef fd3_TetMesh_h
#define fd3_TetMesh_h

#include "fd3/Delaunay.h"
#include "system/Platform.h"
#include "system/ScratchList.h"
#include "system/Stretches.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace fd3
{

using TetId = std::uint32_t;
using VertId = std::uint32_t;
using FaceCode = std::uint32_t; // 4*tet + face

constexpr VertId kInfinite = 0xFFFFFFFFu; // the ghost vertex, at infinity
constexpr VertId kNoVertex = 0xFFFFFFFEu; // "none found"
constexpr TetId kNoTet = 0xFFFFFFFFu;     // "none found"
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
/// (right-hand rule) points out of the tetrahedron: (face, f) is an odd permutation of
/// (0, 1, 2, 3).
constexpr int kFaceVertices[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

enum TetFlag : std::uint32_t
{
  kInCavity = 1,    // in the conflict zone of the point being inserted
  kNotInCavity = 2, // tested during this insertion and kept
  // A free slot. The flag of a cavity's tetrahedra, so that freeing them writes nothing: no
  // live tetrahedron is their neighbour, and an insertion given up clears it.
  kDead = kInCavity
};

/// One tetrahedron's record, located once: for an inner loop that reads several of its fields.
/// TetReader's accessors read through it. Valid until the records move (TetMesh::makeRoom,
/// TetMesh::reserve).
class TetRecord
{
public:
  explicit TetRecord(const std::uint32_t* words) : r_(words) {}

  VertId vertex(int i) const { return i == 0 ? r_[0] & kIdMask : r_[i]; }
  /// The four vertices (v0 without its flags).
  void vertices(VertId out[4]) const
  {
    out[0] = r_[0] & kIdMask;
    out[1] = r_[1];
    out[2] = r_[2];
    out[3] = r_[3];
  }
  /// The vertices of face f, in its outward order (kFaceVertices[f]).
  void faceVertices(int f, VertId out[3]) const
  {
    const int* q = kFaceVertices[f];
    // Only a face's first corner can be vertex 0, whose word holds the flags; when it is vertex 1
    // instead, the mask leaves it as it is (the ghost vertex is only ever vertex 3).
    out[0] = r_[q[0]] & kIdMask;
    out[1] = r_[q[1]];
    out[2] = r_[q[2]];
  }
  FaceCode neighbor(int f) const { return r_[4 + f]; }
  std::uint32_t flags() const { return r_[0] >> kVertexIdBits; }
  bool isGhost() const { return r_[3] == kInfinite; }
  const std::uint32_t* words() const { return r_; }

  static constexpr std::uint32_t kIdMask = kMaxVertices - 1;

private:
  const std::uint32_t* r_;
};

/// A read-only view of a mesh's records, for inner loops: held in a local, the records' address
/// stays in a register, where the mesh's member would be reloaded after every store that might
/// alias it (a byte store aliases everything). Valid until the records move (TetMesh::makeRoom,
/// TetMesh::reserve).
class TetReader
{
public:
  explicit TetReader(const std::uint32_t* words) : words_(words) {}

  TetRecord record(TetId t) const { return TetRecord(words_ + 8 * std::size_t(t)); }
  /// record(tetOf(code)): a face code with its face cleared is an eighth of the record's byte
  /// offset, which an address scales by itself: one AND where the id takes two shifts.
  TetRecord recordOfFace(FaceCode code) const
  {
    return TetRecord(words_ + 2 * std::size_t(code & ~FaceCode(3)));
  }
  VertId vertex(TetId t, int i) const { return record(t).vertex(i); }
  void vertices(TetId t, VertId out[4]) const { record(t).vertices(out); }
  void faceVertices(TetId t, int f, VertId out[3]) const { record(t).faceVertices(f, out); }
  FaceCode neighbor(TetId t, int f) const { return record(t).neighbor(f); }
  FaceCode across(FaceCode code) const { return words_[neighborWord(code)]; }
  std::uint32_t flags(TetId t) const { return record(t).flags(); }
  bool isGhost(TetId t) const { return record(t).isGhost(); }
  bool isDead(TetId t) const { return flags(t) == kDead; }
  /// Starts loading a record, which the caller will need soon (hides memory latency while the
  /// cavity is grown breadth-first).
  void prefetch(TetRecord r) const { fd3::prefetch(r.words()); }
  void prefetch(TetId t) const { prefetch(record(t)); }
  /// prefetch() of the record of a face code's tetrahedron. The face is not cleared: it only
  /// moves the address within the record, in the same cache line (records are 32 bytes, and the
  /// records' array is aligned to a cache line, BulkAllocator.cxx).
  void prefetchOfFace(FaceCode code) const { fd3::prefetch(words_ + 2 * std::size_t(code)); }

protected:
  static constexpr std::uint32_t kIdMask = TetRecord::kIdMask;
  /// The word of face code 4t + f's neighbour, 8t + 4 + f: the code plus itself with f cleared,
  /// two instructions fewer than from t and f.
  static std::size_t neighborWord(FaceCode code)
  {
    return std::size_t(code) + (code & ~FaceCode(3)) + 4;
  }
  const std::uint32_t* words_;
};

/// TetReader's view with the writes (a view, like a span: const, it still writes).
class TetRecords : public TetReader
{
public:
  explicit TetRecords(std::uint32_t* words) : TetReader(words) {}

  void setNeighbor(FaceCode code, FaceCode value) const { word(neighborWord(code)) = value; }
  void setNeighbor(TetRecord r, int f, FaceCode value) const
  {
    const_cast<std::uint32_t*>(r.words())[4 + f] = value;
  }
  void link(FaceCode a, FaceCode b) const
  {
    setNeighbor(a, b);
    setNeighbor(b, a);
  }
  void setFlags(TetRecord r, std::uint32_t flags) const
  {
    std::uint32_t& slot = firstWord(r);
    slot = (slot & kIdMask) | (flags << kVertexIdBits);
  }
  void setFlags(TetId t, std::uint32_t flags) const { setFlags(record(t), flags); }
  /// setFlags() for a tetrahedron whose flags are clear.
  void addFlags(TetRecord r, std::uint32_t flags) const { firstWord(r) |= flags << kVertexIdBits; }
  void addFlags(TetId t, std::uint32_t flags) const { addFlags(record(t), flags); }
  /// Flags a never-written slot dead.
  void markDead(TetId t) const { word(8 * std::size_t(t)) = kDead << kVertexIdBits; }
  /// Writes the whole record of t at once: vertices v (flags clear), no neighbours yet.
  void create(TetId t, const VertId v[4]) const
  {
    std::uint32_t* r = &word(8 * std::size_t(t));
    for (int i = 0; i < 4; ++i)
    {
      r[i] = v[i];
      r[4 + i] = kUnlinked;
    }
  }
  /// Writes the vertices of t: those of `from` (flags clear) with vertex f replaced by p. Its
  /// neighbours are left as they were, for the caller to link all four through the record
  /// returned.
  TetRecord createReplacing(TetId t, TetRecord from, int f, VertId p) const
  {
    std::uint32_t* r = &word(8 * std::size_t(t));
    std::memcpy(r, from.words(), 4 * sizeof(std::uint32_t));
    r[0] &= kIdMask;
    r[f] = p;
    return TetRecord(r);
  }

private:
  // Made from writable words (the constructor's): the view only shares its base's pointer, and
  // every record it hands out points into them.
  std::uint32_t& word(std::size_t i) const { return const_cast<std::uint32_t*>(words_)[i]; }
  static std::uint32_t& firstWord(TetRecord r) { return const_cast<std::uint32_t*>(r.words())[0]; }
};

class TetMesh
{
public:
  /// The records as a raw view (TetReader), for inner loops; every accessor below goes through it.
  TetReader reader() const { return TetReader(records_.data()); }
  TetRecords records() { return TetRecords(records_.data()); }

  VertId vertex(TetId t, int i) const { return reader().vertex(t, i); }
  void vertices(TetId t, VertId out[4]) const { reader().vertices(t, out); }
  FaceCode neighbor(TetId t, int f) const { return reader().neighbor(t, f); }
  FaceCode across(FaceCode code) const { return reader().across(code); }
  std::uint32_t flags(TetId t) const { return reader().flags(t); }
  bool isGhost(TetId t) const { return reader().isGhost(t); }
  bool isDead(TetId t) const { return reader().isDead(t); }
  void prefetch(TetId t) const { reader().prefetch(t); }

  void setNeighbor(FaceCode code, FaceCode value) { records().setNeighbor(code, value); }
  void link(FaceCode a, FaceCode b) { records().link(a, b); }
  void setFlags(TetId t, std::uint32_t flags) { records().setFlags(t, flags); }
  void markDead(TetId t) { records().markDead(t); }
  void create(TetId t, const VertId v[4]) { records().create(t, v); }

  /// Slots ever handed out (live, free, or in a pool's block), the records' high-water mark.
  std::size_t slots() const { return claimed_.load(std::memory_order_relaxed); }

  /// Makes room for `count` more slots than are handed out: records may move, so no pool may
  /// claim at the same time. Beyond the reserved capacity it grows by a quarter at least: the copy
  /// then peaks at 2.25 times the records, not 3 times as with doubling.
  void makeRoom(std::size_t count, const Stretches& copy = nullptr)
  {
    const std::size_t needed = slots() + count;
    // Face codes 4t+f are 32-bit: beyond 2^30 slots (about 150M points) they would wrap.
    if (needed > kMaxTetrahedra)
      throw std::length_error("fd3: more than 2^30 tetrahedra, beyond 32-bit face codes");
    if (needed > capacity())
      reserve(std::max(needed, capacity() + capacity() / 4), copy);
  }
  /// Memory for `count` slots in all (never less than there is). Not initialized: its pages cost
  /// nothing until slots are written. The records move in the stretches of `copy`, where given.
  void reserve(std::size_t count, const Stretches& copy = nullptr)
  {
    if (count <= capacity())
      return;
    IdArray grown;
    grown.reserve(8 * count);
    grown.resize(8 * count);
    forStretches(copy, slots(), [&](std::size_t begin, std::size_t end) {
      std::copy(records_.begin() + 8 * static_cast<std::ptrdiff_t>(begin),
        records_.begin() + 8 * static_cast<std::ptrdiff_t>(end),
        grown.begin() + 8 * static_cast<std::ptrdiff_t>(begin));
    });
    records_.swap(grown);
    // The slots handed out so far, the only ones written: released in even stretches (of the whole
    // block, the first thread's held them all; free() gives back the rest).
    releasePages(copy, grown.data(), 8 * slots() * sizeof(std::uint32_t));
  }
  std::size_t capacity() const { return records_.size() / 8; }

  /// Hands out `count` never-used slots, [first, first + count), or returns false when there is no
  /// room for them. Safe to call from several threads at once.
  bool claim(std::size_t count, TetId& first)
  {
    // Memory reserved ahead may hold more slots than 32-bit face codes name: those are never
    // handed out (makeRoom() then reports the limit).
    const std::size_t limit = std::min(capacity(), kMaxTetrahedra);
    std::size_t taken = claimed_.load(std::memory_order_relaxed);
    do
    {
      if (taken + count > limit)
        return false;
    } while (!claimed_.compare_exchange_weak(taken, taken + count, std::memory_order_relaxed));
    first = static_cast<TetId>(taken);
    return true;
  }

  /// A copy of the records of the slots handed out, as takeRecords() gives them.
  IdArray copyRecords() const
  {
    return IdArray(records_.begin(), records_.begin() + 8 * static_cast<std::ptrdiff_t>(slots()));
  }

  /// Hands the records over (for in-place output conversion); the mesh is empty afterwards.
  /// Record t occupies words 8t..8t+7 for t < slots(), v0 carrying the flags in its top bits.
  IdArray takeRecords()
  {
    records_.resize(8 * slots());
    claimed_ = 0;
    return std::move(records_);
  }

private:
  IdArray records_; // 8 words per slot, slots() of them in use, the rest not yet initialized
  std::atomic<std::size_t> claimed_{0};
};

/// The slots one inserting thread takes new tetrahedra from: those it freed first (the paper's
/// memory management: deleted slots are taken by the next tetrahedra created), then a block of
/// never-used ones claimed from the mesh. One per thread, so that no two threads share a slot.
class SlotPool
{
public:
  /// Slots for `count` new tetrahedra, or false when the mesh has no room left for them (nothing
  /// is taken then).
  bool take(TetMesh& mesh, std::size_t count, TetId* out)
  {
    if (count > free_.size() + (end_ - next_))
    {
      // A new block: the usual size, or just enough when the mesh is nearly full.
      TetId first;
      std::size_t block = std::max(count, kBlock);
      if (!mesh.claim(block, first) && !mesh.claim(block = count, first))
        return false;
      retire(mesh);
      next_ = first;
      end_ = first + static_cast<TetId>(block);
    }
    // The free slots last given first, then the block's.
    const std::size_t reused = std::min(count, free_.size());
    std::reverse_copy(free_.end() - reused, free_.end(), out);
    free_.resize(free_.size() - reused);
    for (std::size_t i = reused; i < count; ++i)
      out[i] = next_++;
    return true;
  }

  /// Frees the slots of the tetrahedra of these face codes (a cavity's deleted ones, which their
  /// flag kInCavity already marks dead): taken again before any new one. All at once: one by
  /// one, each push_back tested the list's capacity.
  void give(const ScratchList<FaceCode>& codes)
  {
    const std::size_t first = free_.size();
    free_.resize(first + codes.size());
    TetId* freed = free_.data() + first;
    for (std::size_t i = 0; i < codes.size(); ++i)
      freed[i] = tetOf(codes[i]);
  }

  /// Frees what is left of the claimed block, so that every slot below mesh.slots() is either
  /// live or dead and listed in a pool.
  void retire(TetMesh& mesh)
  {
    for (; next_ < end_; ++next_)
    {
      mesh.markDead(next_);
      free_.push_back(next_);
    }
  }

  const ScratchList<TetId>& freeSlots() const { return free_; }

  /// Never-used slots claimed at a time.
  static constexpr std::size_t kBlock = 1024;

private:
  ScratchList<TetId> free_;
  TetId next_ = 0, end_ = 0;
};

} // namespace fd3

#endif
