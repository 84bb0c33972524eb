// The regions of a parallel insertion pass (ParallelInsertion.cxx).
#ifndef fd3_ParallelInsertion_h
#define fd3_ParallelInsertion_h

#include "Inserter.h"

#include <cstddef>
#include <vector>

namespace fd3
{

/// Boxes for `parts` threads holding about as many of a pass's points each: a kd split whose
/// level d cuts across axes[d], at quantiles of a sample of the points.
class Partition
{
public:
  Partition(const Mesh& mesh, const IdArray& vertices, int parts, const std::vector<int>& axes);
  int parts() const { return static_cast<int>(regions_.size()); }
  const Region& region(int k) const { return regions_[static_cast<std::size_t>(k)]; }
  /// The region that holds p (as Region::contains() decides).
  int regionOf(const double* p) const;

private:
  struct Node
  {
    int axis; ///< < 0 for a leaf
    double cut;
    int below; ///< a leaf's region
    int above;
  };
  int split(std::size_t begin, std::size_t end, int parts, int depth, const Region& region);

  const Mesh& mesh_;
  const std::vector<int>& axes_;
  std::vector<VertId> sample_;
  std::vector<Node> nodes_; // nodes_[0]: the root
  std::vector<Region> regions_;
};

} // namespace fd3

#endif
