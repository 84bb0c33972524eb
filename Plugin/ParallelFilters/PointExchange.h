/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// Points moved between MPI ranks: the split of space that balances them and the exchange of point
// sets as raw arrays. Nothing in it is particular to Delaunay. A private header of the
// ParallelFilters module.
#ifndef PointExchange_h
#define PointExchange_h

#include "RankGroup.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <array>
#include <cmath>
#include <functional>
#include <vector>

class vtkDataArray;
class vtkPointData;
class vtkPointSet;
class vtkPolyData;

namespace fd3vtk
{
/// A split of space into parts, one per rank: a k-d tree whose leaves are ranks.
class SpaceCuts
{
public:
  using Point = std::array<double, 3>;

  /// The tree of ranks [first, first + ranks) over the points [begin, end): those below the cut
  /// go to the first ranks / 2 ranks, in proportion. Returns the node, or -(rank + 1) for a leaf.
  int Split(
    std::vector<Point>::iterator begin, std::vector<Point>::iterator end, int first, int ranks)
  {
    if (ranks == 1)
    {
      return -(first + 1);
    }
    Point lo = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (auto p = begin; p != end; ++p)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], (*p)[a]);
        hi[a] = std::max(hi[a], (*p)[a]);
      }
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      axis = hi[a] - lo[a] > hi[axis] - lo[axis] ? a : axis;
    }
    const int lower = ranks / 2;
    const auto quantile = begin + (end - begin) * lower / ranks;
    std::nth_element(
      begin, quantile, end, [axis](const Point& a, const Point& b) { return a[axis] < b[axis]; });
    const double at = quantile == end ? HUGE_VAL : (*quantile)[axis];
    const auto split = std::partition(begin, end, [&](const Point& p) { return p[axis] < at; });
    const int node = static_cast<int>(this->Nodes.size());
    this->Nodes.push_back({ axis, at, 0, 0 });
    const int below = this->Split(begin, split, first, lower);
    const int above = this->Split(split, end, first + lower, ranks - lower);
    this->Nodes[node].Below = below;
    this->Nodes[node].Above = above;
    return node;
  }

  int RankOf(const double x[3]) const
  {
    int node = 0;
    while (node >= 0)
    {
      const Cut& cut = this->Nodes[node];
      node = x[cut.Axis] < cut.At ? cut.Below : cut.Above;
    }
    return -node - 1;
  }

private:
  struct Cut
  {
    int Axis;
    double At;
    int Below, Above;
  };
  std::vector<Cut> Nodes;
};

/// The point sets that other ranks sent to this one, one per sender, in rank order.
struct Received
{
  std::vector<vtkSmartPointer<vtkPointSet>> Parts;
  std::vector<int> Senders;
};

/// The point data of `parts` one after the other: the arrays that all of them have, as
/// vtkAppendFilter keeps them.
vtkSmartPointer<vtkPointData> GatherPointData(const std::vector<vtkPointData*>& parts);

/// Points moved between ranks: the split of space that balances them, and the exchange of point
/// sets as raw arrays. Nothing in it is particular to Delaunay.
class PointExchange
{
public:
  explicit PointExchange(RankGroup& ranks) : Ranks(ranks) {}

  /// A split of space into one part per rank, balanced by count: recursive bisection of a
  /// sample of every rank's `finite` points (kSample in all, each rank's share in proportion to
  /// its count), each time across the sample's longest side, at the quantile that gives each side
  /// its share of ranks. Every rank computes it from the same gathered sample, so all agree.
  /// (vtkDistributedPointCloudFilter gives single-precision points under MPI, whatever the
  /// input's, and is several times slower; vtkDIYKdTreeUtilities, whose cuts
  /// vtkRedistributeDataSetFilter uses, is not in ParaView's SDK.)
  bool BalancedCuts(
    vtkDataArray* coordinates, const std::vector<vtkIdType>& finite, SpaceCuts& cuts);

  /// Sends every other rank r the points part(r), made as they are sent, where sendTo[r], and
  /// appends what this rank receives to `received`. With DIY, as vtkDIYDataExchanger, but as raw
  /// arrays: vtkDIYDataExchanger writes each data set as a compressed XML file, which took most of
  /// the redistribution's time.
  bool Send(const std::vector<bool>& sendTo,
    const std::function<vtkSmartPointer<vtkPolyData>(int rank)>& part, Received& received);

private:
  RankGroup& Ranks;
};
} // namespace fd3vtk

#endif
