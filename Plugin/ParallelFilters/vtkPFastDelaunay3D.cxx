/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkPFastDelaunay3D.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCommunicator.h"
#include "vtkDIYUtilities.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSetAttributesFieldList.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformationVector.h"
#include "vtkMPIController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Distributed.h"
#include "fd3/Measures.h"

// clang-format off
#include "vtk_diy2.h"
#include VTK_DIY2(diy/assigner.hpp)
#include VTK_DIY2(diy/link.hpp)
#include VTK_DIY2(diy/master.hpp)
#include VTK_DIY2(diy/mpi.hpp)
// clang-format on

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPFastDelaunay3D);
vtkCxxSetObjectMacro(vtkPFastDelaunay3D, Controller, vtkMultiProcessController);

namespace
{
constexpr const char* kInputIds = "GlobalIds";

/// The point ids `ids` as a vtkIdList.
template <typename Id>
vtkSmartPointer<vtkIdList> IdList(const std::vector<Id>& ids)
{
  auto list = vtkSmartPointer<vtkIdList>::New();
  list->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  std::copy(ids.begin(), ids.end(), list->begin());
  return list;
}

/// `points`, one for each of `from`, with the point data of `from`.
vtkSmartPointer<vtkPolyData> WithPointData(vtkPoints* points, vtkPointData* data, vtkIdList* from)
{
  vtkNew<vtkIdList> to;
  to->SetNumberOfIds(from->GetNumberOfIds());
  std::iota(to->begin(), to->end(), vtkIdType(0));
  auto subset = vtkSmartPointer<vtkPolyData>::New();
  subset->SetPoints(points);
  subset->GetPointData()->CopyAllocate(data, from->GetNumberOfIds());
  subset->GetPointData()->CopyData(data, from, to);
  return subset;
}

/// The points `ids`, from their coordinates (3 components) and point data, as points of `type`.
vtkSmartPointer<vtkPolyData> Subset(
  vtkDataArray* coordinates, vtkPointData* data, const std::vector<vtkIdType>& ids, int type)
{
  vtkSmartPointer<vtkIdList> from = IdList(ids);
  vtkNew<vtkPoints> points;
  points->SetDataType(type);
  points->SetNumberOfPoints(from->GetNumberOfIds());
  coordinates->GetTuples(from, points->GetData());
  return WithPointData(points, data, from);
}

vtkSmartPointer<vtkPolyData> Subset(vtkPointSet* source, const std::vector<vtkIdType>& ids)
{
  vtkPoints* points = source->GetPoints();
  return Subset(points->GetData(), source->GetPointData(), ids, points->GetDataType());
}

/// Doubles x, y, z of points, in the kernel's allocator: resize() does not zero them, which would
/// touch every page once more before they are filled.
using Coordinates = std::vector<double, fd3::BulkAllocator<double>>;

/// Calls visit(i, x) for every point i of a 3-component array, x its coordinates as doubles,
/// without a virtual call per point.
struct VisitPoints
{
  template <typename Array, typename Visit>
  void operator()(Array* coordinates, Visit&& visit) const
  {
    vtkIdType i = 0;
    for (const auto tuple : vtk::DataArrayTupleRange<3>(coordinates))
    {
      const double x[3] = { static_cast<double>(tuple[0]), static_cast<double>(tuple[1]),
        static_cast<double>(tuple[2]) };
      visit(i++, x);
    }
  }
};

template <typename Visit>
void ForEachPoint(vtkDataArray* coordinates, Visit&& visit)
{
  using Reals = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
  if (!Reals::Execute(coordinates, VisitPoints{}, visit))
  {
    VisitPoints{}(coordinates, visit);
  }
}

/// Appends the coordinates of a 3-component array to xyz.
void AppendPoints(vtkDataArray* coordinates, Coordinates& xyz)
{
  ForEachPoint(
    coordinates, [&xyz](vtkIdType, const double x[3]) { xyz.insert(xyz.end(), x, x + 3); });
}

/// The point data of `parts` one after the other: the arrays that all of them have, as
/// vtkAppendFilter keeps them.
vtkSmartPointer<vtkPointData> GatherPointData(const std::vector<vtkPointData*>& parts)
{
  vtkDataSetAttributesFieldList arrays(static_cast<int>(parts.size()));
  vtkIdType count = 0;
  for (vtkPointData* part : parts)
  {
    part == parts[0] ? arrays.InitializeFieldList(part) : arrays.IntersectFieldList(part);
    count += part->GetNumberOfTuples();
  }
  auto data = vtkSmartPointer<vtkPointData>::New();
  data->CopyAllocate(arrays, count);
  vtkIdType next = 0;
  for (std::size_t k = 0; k < parts.size(); ++k)
  {
    const vtkIdType n = parts[k]->GetNumberOfTuples();
    arrays.CopyData(static_cast<int>(k), parts[k], 0, n, data, next);
    next += n;
  }
  return data;
}

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

/// The cells' point ids from `first` on: marked as used in `used` (indexed by id - first), or,
/// with `renumber`, replaced by used[id - first].
struct RenumberIdsFrom
{
  template <typename Array>
  void operator()(Array* ids, std::size_t first, std::vector<vtkIdType>& used, bool renumber) const
  {
    using Id = vtk::GetAPIType<Array>;
    for (auto&& id : vtk::DataArrayValueRange<1>(ids))
    {
      const std::size_t k = static_cast<std::size_t>(id);
      if (k >= first)
      {
        if (renumber)
        {
          id = static_cast<Id>(used[k - first]);
        }
        else
        {
          used[k - first] = 0;
        }
      }
    }
  }
};

void RenumberCellIdsFrom(
  vtkCellArray* cells, std::size_t first, std::vector<vtkIdType>& used, bool renumber)
{
  using Ids = vtkArrayDispatch::DispatchByArray<vtkCellArray::StorageArrayList>;
  vtkDataArray* connectivity = cells->GetConnectivityArray();
  if (!Ids::Execute(connectivity, RenumberIdsFrom{}, first, used, renumber))
  {
    RenumberIdsFrom{}(connectivity, first, used, renumber);
  }
}

/// One execution across the ranks, step by step (see the class documentation).
class DistributedRun
{
public:
  DistributedRun(vtkMultiProcessController* controller)
    : Controller(controller), Rank(controller->GetLocalProcessId()),
      Ranks(controller->GetNumberOfProcesses())
  {}

  /// Step 1: the finite points spread over the ranks by space (BalancedCuts()), this rank's
  /// non-finite ones after them (nothing to triangulate, but they stay in the output as unused
  /// points): their coordinates, as doubles, in Xyz with room for the ghosts, their point data in
  /// OwnData. `points`: the input's, in the output's precision. False when no rank has a point.
  bool Distribute(vtkDataSet* input, vtkPoints* points)
  {
    const vtkIdType count = input ? input->GetNumberOfPoints() : 0;
    std::vector<vtkIdType> counts(this->Ranks);
    this->Controller->AllGather(&count, counts.data(), 1);
    const vtkIdType firstId =
      std::accumulate(counts.begin(), counts.begin() + this->Rank, vtkIdType(0));
    this->InputPoints = std::accumulate(counts.begin(), counts.end(), vtkIdType(0));
    int type = count > 0 ? points->GetDataType() : 0, widest = 0; // as the one-process output's
    this->Controller->AllReduce(&type, &widest, 1, vtkCommunicator::MAX_OP);
    this->PointType = widest > 0 ? widest : VTK_DOUBLE;

    vtkNew<vtkPointData> data;
    if (input)
    {
      data->ShallowCopy(input->GetPointData());
      data->RemoveArray(vtkDataSetAttributes::GhostArrayName());
    }
    vtkNew<vtkIdTypeArray> inputIds;
    inputIds->SetName(kInputIds);
    inputIds->SetNumberOfValues(count);
    std::iota(inputIds->GetPointer(0), inputIds->GetPointer(0) + count, firstId);
    std::vector<vtkIdType> finite, nonFinite;
    ForEachPoint(points->GetData(), [&](vtkIdType i, const double x[3]) {
      (fd3::isFinite(x) ? finite : nonFinite).push_back(i);
    });
    data->AddArray(inputIds);
    std::vector<vtkSmartPointer<vtkPointSet>> parts;
    std::vector<int> senders;
    int mine = !finite.empty(), any = 0;
    this->Controller->AllReduce(&mine, &any, 1, vtkCommunicator::MAX_OP);
    if (any)
    {
      const SpaceCuts cuts = this->BalancedCuts(points->GetData(), finite);
      std::vector<std::vector<vtkIdType>> lists(this->Ranks);
      ForEachPoint(points->GetData(), [&](vtkIdType i, const double x[3]) {
        if (fd3::isFinite(x))
        {
          lists[cuts.RankOf(x)].push_back(i);
        }
      });
      finite = std::vector<vtkIdType>();
      this->Send(
        lists, [&](int r) { return Subset(points->GetData(), data, lists[r], this->PointType); },
        parts, senders);
      if (!lists[this->Rank].empty()) // in rank order
      {
        const auto at =
          std::upper_bound(senders.begin(), senders.end(), this->Rank) - senders.begin();
        parts.insert(
          parts.begin() + at, Subset(points->GetData(), data, lists[this->Rank], this->PointType));
        senders.insert(senders.begin() + at, this->Rank);
      }
    }
    this->FiniteCount = 0;
    for (const auto& part : parts)
    {
      this->FiniteCount += static_cast<std::size_t>(part->GetNumberOfPoints());
    }
    if (!nonFinite.empty() || parts.empty())
    {
      parts.push_back(Subset(points->GetData(), data, nonFinite, this->PointType));
    }
    this->OwnCount = this->FiniteCount + nonFinite.size();
    this->Xyz.reserve(3 * (this->OwnCount + this->GhostRoom()));
    std::vector<vtkPointData*> partData;
    for (const auto& part : parts)
    {
      AppendPoints(part->GetPoints()->GetData(), this->Xyz);
      partData.push_back(part->GetPointData());
    }
    this->OwnData = GatherPointData(partData);
    return this->InputPoints > 0;
  }

  /// A split of space into one part per rank, balanced by count: recursive bisection of a sample
  /// of every rank's `finite` points (kSample in all, each rank's share in proportion to its
  /// count), each time across the sample's longest side, at the quantile that gives each side
  /// its share of ranks. Every rank computes it from the same gathered sample, so all agree.
  /// (vtkDistributedPointCloudFilter gives single-precision points under MPI, whatever the
  /// input's, and is several times slower; vtkDIYKdTreeUtilities, whose cuts
  /// vtkRedistributeDataSetFilter uses, is not in ParaView's SDK.)
  SpaceCuts BalancedCuts(vtkDataArray* coordinates, const std::vector<vtkIdType>& finite)
  {
    constexpr double kSample = 1 << 18; // 6 MB gathered; parts within about 1% of the mean
    const vtkIdType local = static_cast<vtkIdType>(finite.size());
    vtkIdType total = 0;
    this->Controller->AllReduce(&local, &total, 1, vtkCommunicator::SUM_OP);
    const std::size_t mine =
      static_cast<std::size_t>(std::ceil(kSample * double(local) / double(total)));
    std::vector<double> sample(3 * std::min(mine, finite.size()));
    for (std::size_t k = 0; k < sample.size() / 3; ++k)
    {
      coordinates->GetTuple(finite[k * finite.size() / (sample.size() / 3)], &sample[3 * k]);
    }
    std::vector<vtkIdType> lengths(this->Ranks), offsets(this->Ranks);
    const vtkIdType length = static_cast<vtkIdType>(sample.size());
    this->Controller->AllGather(&length, lengths.data(), 1);
    std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
    std::vector<std::array<double, 3>> all(
      static_cast<std::size_t>(offsets.back() + lengths.back()) / 3);
    this->Controller->AllGatherV(
      sample.data(), all.data()->data(), length, lengths.data(), offsets.data());
    SpaceCuts cuts;
    cuts.Split(all.begin(), all.end(), 0, this->Ranks);
    return cuts;
  }

  /// Sends every other rank r the points part(r), made when sent, where lists[r] is not empty;
  /// what this rank receives, one set per sender, in rank order, with its sender.
  /// With DIY, as vtkDIYDataExchanger, but as raw arrays: vtkDIYDataExchanger writes each data
  /// set as a compressed XML file, which took most of the redistribution's time.
  template <typename List, typename Part>
  void Send(const std::vector<List>& lists, Part&& part,
    std::vector<vtkSmartPointer<vtkPointSet>>& received, std::vector<int>& senders)
  {
    diy::mpi::communicator comm = vtkDIYUtilities::GetCommunicator(this->Controller);
    std::vector<int> sends(this->Ranks);
    for (int r = 0; r < this->Ranks; ++r)
    {
      sends[r] = r != this->Rank && !lists[r].empty();
    }
    std::vector<std::vector<int>> allSends;
    diy::mpi::all_gather(comm, sends, allSends);
    diy::Master master(comm, 1, -1, nullptr, [](void*) {});
    diy::ContiguousAssigner assigner(this->Ranks, this->Ranks);
    auto* link = new diy::Link(); // the master's
    for (int r = 0; r < this->Ranks; ++r)
    {
      if (allSends[this->Rank][r] || allSends[r][this->Rank])
      {
        link->add_neighbor(diy::BlockID(r, assigner.rank(r)));
      }
    }
    int block = 0; // DIY's one block per rank; its content is not used
    master.add(this->Rank, &block, link);
    master.foreach ([&](void*, const diy::Master::ProxyWithLink& proxy) {
      for (const diy::BlockID& to : proxy.link()->neighbors())
      {
        if (sends[to.gid])
        {
          vtkSmartPointer<vtkPolyData> points = part(to.gid);
          proxy.enqueue<vtkDataArray*>(to, points->GetPoints()->GetData());
          proxy.enqueue<vtkFieldData*>(to, points->GetPointData());
        }
      }
    });
    master.exchange();
    std::vector<vtkSmartPointer<vtkPointSet>> byRank(this->Ranks);
    master.foreach ([&](void*, const diy::Master::ProxyWithLink& proxy) {
      for (const diy::BlockID& from : proxy.link()->neighbors())
      {
        if (proxy.incoming(from.gid))
        {
          vtkDataArray* xyz = nullptr;
          vtkFieldData* values = nullptr;
          proxy.dequeue<vtkDataArray*>(from.gid, xyz);
          proxy.dequeue<vtkFieldData*>(from.gid, values);
          byRank[from.gid] = vtkSmartPointer<vtkPolyData>::New();
          byRank[from.gid]->SetPoints(vtkNew<vtkPoints>());
          byRank[from.gid]->GetPoints()->SetData(vtkSmartPointer<vtkDataArray>::Take(xyz));
          byRank[from.gid]->GetPointData()->ShallowCopy(
            vtkSmartPointer<vtkFieldData>::Take(values));
        }
      }
    });
    for (int r = 0; r < this->Ranks; ++r)
    {
      if (byRank[r] && byRank[r]->GetNumberOfPoints() > 0)
      {
        received.push_back(byRank[r]);
        senders.push_back(r);
      }
    }
  }

  /// The ghost points that room is made for up front, in Xyz and in the kernel's vertex records: a
  /// rank receives a few percent of its own count at 1M points a rank, more on small ones. Growing
  /// either later would copy it, and under MPI the copy's source stays resident (Open MPI keeps
  /// the freed pages).
  std::size_t GhostRoom() const { return this->OwnCount / 4 + 1024; }

  /// Step 2: one exact frame for every rank, from the global bounds and the shifts that are
  /// exact on every rank.
  fd3::Frame Frame()
  {
    fd3::Bounds box = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
      VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (std::size_t i = 0; i < this->FiniteCount; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        box[2 * a] = std::min(box[2 * a], this->Xyz[3 * i + a]);
        box[2 * a + 1] = std::max(box[2 * a + 1], this->Xyz[3 * i + a]);
      }
    }
    this->Boxes.assign(this->Ranks, fd3::Bounds());
    this->Controller->AllGather(box.data(), this->Boxes[0].data(), 6);
    double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (const fd3::Bounds& b : this->Boxes)
    {
      for (int a = 0; a < 3 && b[0] <= b[1]; ++a)
      {
        lo[a] = std::min(lo[a], b[2 * a]);
        hi[a] = std::max(hi[a], b[2 * a + 1]);
      }
    }
    bool exact[3] = { true, true, true };
    fd3::checkShifts(this->Xyz.data(), this->OwnCount, lo, hi, exact);
    int local[3] = { exact[0], exact[1], exact[2] }, global[3];
    this->Controller->AllReduce(local, global, 3, vtkCommunicator::MIN_OP);
    for (int a = 0; a < 3; ++a)
    {
      exact[a] = global[a] != 0;
    }
    const double bounds[6] = { lo[0], hi[0], lo[1], hi[1], lo[2], hi[2] };
    this->Diagonal = fd3::diagonal(bounds);
    const fd3::Frame frame = fd3::frameFor(lo, hi, exact);
    int fits = fd3::fitsFrame(frame, this->Xyz.data(), this->OwnCount), allFit = 0;
    this->Controller->AllReduce(&fits, &allFit, 1, vtkCommunicator::MIN_OP);
    return allFit ? frame : fd3::identityFrame(lo, hi);
  }

  /// Step 3: this rank's points tetrahedralized, and the halo of every other rank sent to it.
  void Exchange(fd3::IncrementalDelaunay& mesh)
  {
    std::vector<fd3::Bounds> others = this->Boxes;
    others[this->Rank] = { 1, -1, 1, -1, 1, -1 };
    std::vector<std::vector<std::uint32_t>> halo = mesh.haloVertices(others);
    if (mesh.status() != fd3::Status::Ok) // no tetrahedron to choose from: every point might matter
    {
      for (int r = 0; r < this->Ranks; ++r)
      {
        if (r != this->Rank)
        {
          halo[r].resize(this->FiniteCount);
          std::iota(halo[r].begin(), halo[r].end(), 0u);
        }
      }
    }
    // Their coordinates from Xyz, made as each part is sent (with no tetrahedron, a rank sends all
    // its points to every other), or from the mesh's records once Xyz is dropped, all at once.
    const std::vector<std::vector<double>> fromMesh =
      this->PointsInMesh ? mesh.points(halo) : std::vector<std::vector<double>>();
    this->Send(
      halo,
      [&](int r) {
        return this->HaloPart(halo[r], this->PointsInMesh ? fromMesh[r] : this->PointsOf(halo[r]));
      },
      this->Ghosts, this->GhostSenders);
  }

  /// The coordinates of own points `ids` in Xyz, 3 each.
  std::vector<double> PointsOf(const std::vector<std::uint32_t>& ids) const
  {
    std::vector<double> xyz;
    xyz.reserve(3 * ids.size());
    for (const std::uint32_t id : ids)
    {
      xyz.insert(xyz.end(), &this->Xyz[3 * std::size_t(id)], &this->Xyz[3 * std::size_t(id) + 3]);
    }
    return xyz;
  }

  /// The own points `halo`, at `xyz` (3 each), with their point data.
  vtkSmartPointer<vtkPolyData> HaloPart(
    const std::vector<std::uint32_t>& halo, const std::vector<double>& xyz)
  {
    vtkNew<vtkPoints> points;
    points->SetDataType(this->PointType);
    points->SetNumberOfPoints(static_cast<vtkIdType>(halo.size()));
    for (std::size_t k = 0; k < halo.size(); ++k)
    {
      points->SetPoint(static_cast<vtkIdType>(k), &xyz[3 * k]);
    }
    return WithPointData(points, this->OwnData, IdList(halo));
  }

  /// Frees Xyz once the mesh has read the points into its records, which give them back exactly
  /// (fd3::recoverable()), so that it is not in the peak, the mesh's. The non-finite points, which
  /// the mesh does not hold, are kept aside.
  void DropPoints()
  {
    this->NonFinite.assign(
      this->Xyz.begin() + 3 * this->FiniteCount, this->Xyz.begin() + 3 * this->OwnCount);
    Coordinates().swap(this->Xyz);
    this->PointsInMesh = true;
  }

  /// Step 4: the received points added to this rank's mesh; the owner of every vertex.
  fd3::Triangulation AddGhosts(fd3::IncrementalDelaunay& mesh)
  {
    Coordinates ghostXyz;
    for (const auto& ghosts : this->Ghosts)
    {
      AppendPoints(ghosts->GetPoints()->GetData(), ghostXyz);
    }
    mesh.add(ghostXyz.data(), ghostXyz.size() / 3);
    fd3::Triangulation result;
    if (this->PointsInMesh)
    {
      this->Xyz.resize(3 * this->OwnCount + ghostXyz.size()); // not filled: no page is touched yet
      result = mesh.release(this->Xyz.data());
      std::copy(
        this->NonFinite.begin(), this->NonFinite.end(), this->Xyz.begin() + 3 * this->FiniteCount);
      // The release wrote the ghosts too, but they are other ranks' points, which this rank did
      // not check with fd3::recoverable().
      std::copy(ghostXyz.begin(), ghostXyz.end(), this->Xyz.begin() + 3 * this->OwnCount);
    }
    else
    {
      result = mesh.release();
      this->Xyz.insert(this->Xyz.end(), ghostXyz.begin(), ghostXyz.end());
    }
    // Made after the release, which gives back most of the mesh.
    this->Owner.assign(this->OwnCount, this->Rank);
    for (std::size_t k = 0; k < this->Ghosts.size(); ++k)
    {
      this->Owner.insert(this->Owner.end(),
        static_cast<std::size_t>(this->Ghosts[k]->GetNumberOfPoints()), this->GhostSenders[k]);
    }
    return result;
  }

  /// Whether this rank owns the simplex: it owns its lexicographically smallest vertex, which
  /// every rank holding the simplex finds alike. A vertex cell (a point on no other cell of the
  /// alpha shape, or a duplicate) goes with the point itself. Every position is one rank's
  /// alone: the cuts send a point by its coordinates, so the copies of a position go to one rank
  /// (which merges them) and no ghost repeats an own point.
  bool Owns(const std::uint32_t* ids, int size) const
  {
    // Nearly always one rank owns every vertex, and their order does not matter.
    const int owner = this->Owner[ids[0]];
    if (std::all_of(ids + 1, ids + size, [&](std::uint32_t v) { return this->Owner[v] == owner; }))
    {
      return owner == this->Rank;
    }
    const std::uint32_t* smallest =
      std::min_element(ids, ids + size, [this](std::uint32_t a, std::uint32_t b) {
        return std::lexicographical_compare(
          &this->Xyz[3 * a], &this->Xyz[3 * a + 3], &this->Xyz[3 * b], &this->Xyz[3 * b + 3]);
      });
    return this->Owner[*smallest] == this->Rank;
  }

  /// Step 5: the output's points: this rank's own, then the received ones its cells use (as
  /// duplicate points, in the order received), with the cells' ids renumbered to match.
  void SetOutputPoints(vtkUnstructuredGrid* output)
  {
    std::vector<vtkIdType> ghostId(this->Xyz.size() / 3 - this->OwnCount, -1);
    RenumberCellIdsFrom(output->GetCells(), this->OwnCount, ghostId, false);
    vtkIdType next = static_cast<vtkIdType>(this->OwnCount);
    for (vtkIdType& id : ghostId)
    {
      id = id == 0 ? next++ : -1;
    }
    RenumberCellIdsFrom(output->GetCells(), this->OwnCount, ghostId, true);

    vtkNew<vtkPoints> points;
    points->SetDataType(this->PointType);
    points->SetNumberOfPoints(next);
    vtkDataArray* coordinates = points->GetData();
    for (std::size_t i = 0; i < this->OwnCount; ++i)
    {
      coordinates->SetTuple(static_cast<vtkIdType>(i), &this->Xyz[3 * i]);
    }
    for (std::size_t g = 0; g < ghostId.size(); ++g)
    {
      if (ghostId[g] >= 0)
      {
        coordinates->SetTuple(ghostId[g], &this->Xyz[3 * (this->OwnCount + g)]);
      }
    }
    output->SetPoints(points);

    std::vector<vtkSmartPointer<vtkPolyData>> used;
    std::vector<vtkPointData*> parts{ this->OwnData };
    std::size_t g = 0;
    for (const auto& ghosts : this->Ghosts)
    {
      std::vector<vtkIdType> ids;
      for (vtkIdType i = 0; i < ghosts->GetNumberOfPoints(); ++i, ++g)
      {
        if (ghostId[g] >= 0)
        {
          ids.push_back(i);
        }
      }
      used.push_back(Subset(ghosts, ids));
      parts.push_back(used.back()->GetPointData());
    }
    output->GetPointData()->ShallowCopy(GatherPointData(parts));
    vtkPointData* data = output->GetPointData();
    data->SetGlobalIds(data->GetArray(kInputIds));
    vtkNew<vtkUnsignedCharArray> ghostType;
    ghostType->SetName(vtkDataSetAttributes::GhostArrayName());
    ghostType->SetNumberOfValues(next);
    std::fill_n(ghostType->GetPointer(0), this->OwnCount, 0);
    std::fill(ghostType->GetPointer(0) + this->OwnCount, ghostType->GetPointer(0) + next,
      static_cast<unsigned char>(vtkDataSetAttributes::DUPLICATEPOINT));
    data->AddArray(ghostType);
  }

  /// The figures of all ranks: counts summed (each vertex and tetrahedron counted by its owner),
  /// times the slowest rank's.
  fd3::Statistics GlobalFigures(const fd3::Triangulation& result)
  {
    const fd3::Statistics& s = result.stats;
    std::size_t ownedTetrahedra = 0;
    for (std::size_t t = 0; t < result.numberOfTetrahedra(); ++t)
    {
      ownedTetrahedra += this->Owns(result.tetrahedra.data() + 4 * t, 4);
    }
    std::size_t inserted = 0, skipped = 0, merged = 0;
    for (std::size_t k = 0; k < this->OwnCount && result.status == fd3::Status::Ok; ++k)
    {
      const std::uint32_t v = result.representative[k];
      inserted += v == k;
      if (v != k && v != fd3::kNoPoint)
      {
        (this->SamePosition(k, v) ? merged : skipped) += 1;
      }
    }
    std::array<double, 10> sums = { double(s.nonFinitePoints), double(inserted), double(skipped),
      double(ownedTetrahedra), double(s.walkSteps), double(s.cavityTetrahedra),
      double(s.integerExact), double(s.insertedPoints),
      double(this->Xyz.size() / 3 - this->OwnCount), double(merged) },
                           total;
    std::array<double, 7> maxima = { double(s.maxWalkSteps), s.secondsSort, s.secondsLocate,
      s.secondsCavity, s.secondsFill, s.secondsOutput, s.secondsTotal },
                          slowest;
    this->Controller->AllReduce(sums.data(), total.data(), sums.size(), vtkCommunicator::SUM_OP);
    this->Controller->AllReduce(
      maxima.data(), slowest.data(), maxima.size(), vtkCommunicator::MAX_OP);
    fd3::Statistics global;
    global.inputPoints = static_cast<std::size_t>(this->InputPoints);
    global.nonFinitePoints = static_cast<std::size_t>(total[0]);
    global.insertedPoints = static_cast<std::size_t>(total[1]);
    global.closePointsSkipped = static_cast<std::size_t>(total[2]);
    global.duplicatesMerged = static_cast<std::size_t>(total[9]);
    global.tetrahedra = static_cast<std::size_t>(total[3]);
    // Walks and cavities of ghost insertions count too: that is the work done.
    global.walkSteps = static_cast<std::size_t>(total[4] * total[1] / std::max(total[7], 1.0));
    global.cavityTetrahedra =
      static_cast<std::size_t>(total[5] * total[1] / std::max(total[7], 1.0));
    global.integerExact = static_cast<std::size_t>(total[6]);
    this->GhostPoints = static_cast<vtkIdType>(total[8]);
    global.maxWalkSteps = static_cast<std::size_t>(slowest[0]);
    global.secondsSort = slowest[1];
    global.secondsLocate = slowest[2];
    global.secondsCavity = slowest[3];
    global.secondsFill = slowest[4];
    global.secondsOutput = slowest[5];
    global.secondsTotal = slowest[6];
    return global;
  }

  /// Steps 3 and 4 on every rank: this rank's mesh, the exchange, the received points added.
  /// False on every rank when any rank failed or was aborted (so that none waits for it in a
  /// collective call); `failure` then says why on a rank that failed.
  bool Triangulate(const fd3::Options& options, const fd3::Frame& frame, fd3::Triangulation& result,
    std::string& failure)
  {
    using Clock = std::chrono::steady_clock;
    std::unique_ptr<fd3::IncrementalDelaunay> mesh;
    auto start = Clock::now();
    double seconds = 0; // meshing only: the exchange is left out
    const bool recoverable =
      options.tolerance == 0 && fd3::recoverable(frame, this->Xyz.data(), this->FiniteCount);
    try
    {
      mesh = std::make_unique<fd3::IncrementalDelaunay>(this->Xyz.data(), this->OwnCount, options,
        frame, this->GhostRoom(),
        recoverable ? std::function<void()>([this] { this->DropPoints(); }) : nullptr);
    }
    catch (const std::exception& error) // out of memory, too many points
    {
      failure = error.what();
    }
    if (!this->AllSucceeded(mesh && mesh->status() != fd3::Status::Aborted))
    {
      return false;
    }
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    this->Exchange(*mesh);
    start = Clock::now();
    try
    {
      result = this->AddGhosts(*mesh);
      result.stats.secondsTotal =
        seconds + std::chrono::duration<double>(Clock::now() - start).count();
    }
    catch (const std::exception& error) // aborted, or out of memory
    {
      if (mesh->status() != fd3::Status::Aborted)
      {
        failure = error.what();
      }
      result.status = fd3::Status::Aborted;
    }
    return this->AllSucceeded(result.status != fd3::Status::Aborted);
  }

  /// Whether every rank got through the last step (a rank that failed or was aborted makes all
  /// of them stop, so that none waits in a collective call for it).
  bool AllSucceeded(bool succeeded)
  {
    int local = succeeded, global = 0;
    this->Controller->AllReduce(&local, &global, 1, vtkCommunicator::MIN_OP);
    return global != 0;
  }

  /// The status of the whole: Ok when any rank has tetrahedra, else the most telling one.
  fd3::Status GlobalStatus(fd3::Status local)
  {
    auto rankOf = [](fd3::Status s) {
      return s == fd3::Status::Ok        ? 3
        : s == fd3::Status::Degenerate   ? 2
        : s == fd3::Status::TooFewPoints ? 1
                                         : 0;
    };
    int mine = rankOf(local), best = 0;
    this->Controller->AllReduce(&mine, &best, 1, vtkCommunicator::MAX_OP);
    const fd3::Status byRank[] = { fd3::Status::Empty, fd3::Status::TooFewPoints,
      fd3::Status::Degenerate, fd3::Status::Ok };
    return byRank[best];
  }

  bool SamePosition(std::size_t a, std::size_t b) const
  {
    return std::equal(&this->Xyz[3 * a], &this->Xyz[3 * a + 3], &this->Xyz[3 * b]);
  }

  vtkMultiProcessController* Controller;
  const int Rank;
  const int Ranks;
  vtkIdType InputPoints = 0;
  vtkIdType GhostPoints = 0;
  double Diagonal = 0;
  vtkSmartPointer<vtkPointData>
    OwnData; ///< of this rank's points: finite ones by space, then its NaN/Inf
  std::size_t OwnCount = 0;
  std::size_t FiniteCount = 0;    ///< the first own points, the finite ones
  int PointType = VTK_DOUBLE;     ///< of the output's points
  Coordinates Xyz;                ///< own points, then the received ones (not while PointsInMesh)
  bool PointsInMesh = false;      ///< Xyz dropped while the mesh holds the points
  std::vector<double> NonFinite;  ///< own non-finite points, while PointsInMesh
  std::vector<fd3::Bounds> Boxes; ///< every rank's bounds
  std::vector<vtkSmartPointer<vtkPointSet>> Ghosts; ///< received, one set per sender
  std::vector<int> GhostSenders;
  std::vector<int> Owner; ///< per point: the rank whose own point it is
};
} // namespace

vtkPFastDelaunay3D::vtkPFastDelaunay3D()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPFastDelaunay3D::~vtkPFastDelaunay3D()
{
  this->SetController(nullptr);
}

int vtkPFastDelaunay3D::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->NumberOfGhostPoints = 0;
  if (!vtkMPIController::SafeDownCast(this->Controller) ||
    this->Controller->GetNumberOfProcesses() < 2)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  output->Initialize();
  this->RecordFigures(fd3::Statistics());
  if (this->BoundingTriangulation)
  {
    vtkErrorMacro("BoundingTriangulation is not available across MPI ranks; the output is empty");
    return 1;
  }

  DistributedRun run(this->Controller);
  if (!run.Distribute(input, InputPoints(input, this->OutputPointsPrecision)))
  {
    if (this->Controller->GetLocalProcessId() == 0)
    {
      vtkWarningMacro("Cannot triangulate; no input points");
    }
    SetPointsWithoutCells(output, nullptr, nullptr);
    return 1;
  }
  const fd3::Frame frame = run.Frame();
  fd3::Triangulation result;
  std::string failure;
  const bool done = run.Triangulate(this->KernelOptions(run.Diagonal), frame, result, failure);
  if (!failure.empty())
  {
    vtkErrorMacro("Triangulation failed: " << failure << "; the output is empty");
  }
  if (!done)
  {
    // Every rank stops as the one that aborted or failed, and runs again on the next update as
    // an aborted filter does; else that rank alone would, and wait for the others.
    this->SetAbortOutput(true);
    return 1;
  }

  const auto outputStart = std::chrono::steady_clock::now();
  const fd3::Status status = run.GlobalStatus(result.status);
  fd3::Statistics figures = run.GlobalFigures(result);
  this->NumberOfGhostPoints = run.GhostPoints;
  if (status == fd3::Status::Ok && result.status == fd3::Status::Ok)
  {
    this->SetOutputCells(output, run.Xyz.data(), run.Xyz.size() / 3, result,
      [&run](const std::uint32_t* ids, int size) { return run.Owns(ids, size); });
    run.SetOutputPoints(output);
    std::vector<double> converted;
    this->AddCellArrays(output, CoordinatesAsDoubles(output->GetPoints(), converted));
  }
  figures.secondsOutput +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - outputStart).count();
  this->RecordFigures(figures);
  if (this->Controller->GetLocalProcessId() == 0) // one report for all ranks
  {
    this->ReportOnInput(status, figures, static_cast<vtkIdType>(figures.inputPoints));
  }
  if (status != fd3::Status::Ok)
  {
    SetPointsWithoutCells(output, InputPoints(input, this->OutputPointsPrecision),
      input ? input->GetPointData() : nullptr);
    return 1;
  }
  this->AddFigures(output->GetFieldData());
  return 1;
}

void vtkPFastDelaunay3D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "NumberOfGhostPoints: " << this->NumberOfGhostPoints << "\n";
}
