// The vertices of a periodic run: images p + kL of the input points, where L is the box's period
// on each axis. Such an image is in general no double (0.1 + 1 needs 57 bits), so a vertex record
// holds its rounding and this table the rest, which the predicates' exact stages add back: every
// sign is then the one of the exact images, and a configuration and its translates by whole
// periods get the same answers. The symbolic perturbation orders images by their input point and
// then their offset, an order that translating every vertex by one period keeps (precedes()).
#ifndef fd3_PeriodicImages_h
#define fd3_PeriodicImages_h

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fd3
{

/// A vertex's image: its exact coordinates are its record's plus `residual`, a double each (the
/// exact sum of two doubles is their rounded sum plus a double).
struct ImageOf
{
  double residual[3];
  /// The input point it is an image of, as given: the perturbation's order compares it.
  double source[3];
  /// The periods it was moved by, from `source`.
  std::int32_t offset[3];
  /// perturbationKey() of `source`.
  std::uint16_t key;
};

/// x + periods * period exactly, as its rounding to nearest and the residual, a double (the
/// records and ImageOf::residual of PeriodicDelaunay's images). False where the residual is no
/// double (the exact value spans more than two doubles' bits) or the result is not finite.
bool translateExactly(
  double x, std::int64_t periods, double period, double& rounded, double& residual);

/// Whether a precedes b in the perturbation's order of images: by key, then source, then offset.
inline bool precedes(const ImageOf& a, const ImageOf& b)
{
  if (a.key != b.key)
    return a.key < b.key;
  if (!std::equal(a.source, a.source + 3, b.source))
    return std::lexicographical_compare(a.source, a.source + 3, b.source, b.source + 3);
  return std::lexicographical_compare(a.offset, a.offset + 3, b.offset, b.offset + 3);
}

/// The images of a mesh's vertices, by vertex rank, found from a pointer to a vertex record's
/// coordinates. Read by every inserter during a pass; changed (at()'s records, with more vertices)
/// between passes only.
class PeriodicImages
{
public:
  /// The records' coordinates: vertex v's at records + v * stride.
  void locate(const double* records, std::size_t stride)
  {
    records_ = records;
    stride_ = stride;
  }
  void append(const ImageOf& image) { byRank_.push_back(image); }
  void append(const std::vector<ImageOf>& more)
  {
    byRank_.insert(byRank_.end(), more.begin(), more.end());
  }
  /// The images of every vertex so far (by rank), in place of any before.
  void assign(std::vector<ImageOf> byRank) { byRank_ = std::move(byRank); }
  ImageOf& at(std::size_t rank) { return byRank_[rank]; }
  std::size_t size() const { return byRank_.size(); }

  /// The image whose record holds p, or null for a point that is no vertex record.
  const ImageOf* find(const double* p) const
  {
    // As addresses: p may point into another array, which pointer arithmetic may not compare.
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t first = reinterpret_cast<std::uintptr_t>(records_);
    const std::size_t step = stride_ * sizeof(double);
    if (at < first || at - first >= byRank_.size() * step || (at - first) % step != 0)
      return nullptr;
    return &byRank_[(at - first) / step];
  }

private:
  std::vector<ImageOf> byRank_;
  const double* records_ = nullptr;
  std::size_t stride_ = 1;
};

} // namespace fd3

#endif
