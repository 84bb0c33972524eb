/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "DistributedRun.h"

#include "FilterInput.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCommunicator.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Distributed.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <iterator>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace fd3vtk
{
namespace
{
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

/// Marks the point ids from `first` on that the cells use: used[id - first] = 0.
struct MarkIdsFrom
{
  template <typename Array>
  void operator()(Array* ids, std::size_t first, std::vector<vtkIdType>& used) const
  {
    for (const auto id : vtk::DataArrayValueRange<1>(ids))
    {
      if (static_cast<std::size_t>(id) >= first)
      {
        used[static_cast<std::size_t>(id) - first] = 0;
      }
    }
  }
};

/// Replaces the cells' point ids from `first` on by newId[id - first].
struct RenumberIdsFrom
{
  template <typename Array>
  void operator()(Array* ids, std::size_t first, const std::vector<vtkIdType>& newId) const
  {
    using Id = vtk::GetAPIType<Array>;
    for (auto&& id : vtk::DataArrayValueRange<1>(ids))
    {
      if (static_cast<std::size_t>(id) >= first)
      {
        id = static_cast<Id>(newId[static_cast<std::size_t>(id) - first]);
      }
    }
  }
};

/// Runs `worker` on the cells' connectivity array, without a virtual call per id.
template <typename Worker, typename... Args>
void OnCellIds(vtkCellArray* cells, Worker worker, Args&... args)
{
  using Ids = vtkArrayDispatch::DispatchByArray<vtkCellArray::StorageArrayList>;
  vtkDataArray* connectivity = cells->GetConnectivityArray();
  if (!Ids::Execute(connectivity, worker, args...))
  {
    worker(connectivity, args...);
  }
}

/// The input pieces' point ids in rank order, as the "GlobalIds" array of each point, and where
/// given, the points' weights (kWeights).
vtkSmartPointer<vtkPointData> InputData(
  vtkDataSet* input, vtkIdType count, vtkIdType firstId, const std::vector<double>* weights)
{
  auto data = vtkSmartPointer<vtkPointData>::New();
  if (input)
  {
    data->ShallowCopy(input->GetPointData());
    data->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  }
  vtkNew<vtkIdTypeArray> inputIds;
  inputIds->SetName(kInputIds);
  inputIds->SetNumberOfValues(count);
  std::iota(inputIds->GetPointer(0), inputIds->GetPointer(0) + count, firstId);
  data->AddArray(inputIds);
  if (weights)
  {
    vtkNew<vtkDoubleArray> values;
    values->SetName(kWeights);
    values->SetNumberOfValues(count);
    std::copy_n(
      weights->begin(), std::min<std::size_t>(weights->size(), count), values->GetPointer(0));
    data->AddArray(values);
  }
  return data;
}

/// One rank's figures, then all ranks' together (Reduce()): counts are summed, with each vertex
/// and tetrahedron counted by its owner; times are the slowest rank's.
struct RankFigures
{
  fd3::Statistics Stats;
  double MeshInsertions = 0; ///< vertices of the rank's mesh, ghosts included
  double Ghosts = 0;         ///< points received

  void Reduce(vtkMultiProcessController* controller)
  {
    SumFigures(controller, this->Stats);
    const double sums[2] = { this->MeshInsertions, this->Ghosts };
    double total[2];
    controller->AllReduce(sums, total, 2, vtkCommunicator::SUM_OP);
    this->MeshInsertions = total[0];
    this->Ghosts = total[1];
    // Walks and cavities of ghost insertions count too: that is the work done.
    const double perVertex =
      double(this->Stats.insertedPoints) / std::max(this->MeshInsertions, 1.0);
    this->Stats.walkSteps = static_cast<std::size_t>(double(this->Stats.walkSteps) * perVertex);
    this->Stats.cavityTetrahedra =
      static_cast<std::size_t>(double(this->Stats.cavityTetrahedra) * perVertex);
  }
};

/// Which of the lists hold something.
template <typename List>
std::vector<bool> NonEmpty(const std::vector<List>& lists)
{
  std::vector<bool> nonEmpty(lists.size());
  for (std::size_t r = 0; r < lists.size(); ++r)
  {
    nonEmpty[r] = !lists[r].empty();
  }
  return nonEmpty;
}

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

fd3::Status StatusOfAllRanks(vtkMultiProcessController* controller, fd3::Status mine)
{
  // The order of the statuses across ranks, from the least telling.
  constexpr fd3::Status kByRank[] = { fd3::Status::Empty, fd3::Status::TooFewPoints,
    fd3::Status::Degenerate, fd3::Status::Ok, fd3::Status::OutOfRange, fd3::Status::CheckFailed };
  constexpr int kLast = static_cast<int>(std::size(kByRank)) - 1;
  const int rank = std::min(
    static_cast<int>(std::find(std::begin(kByRank), std::end(kByRank), mine) - kByRank), kLast);
  int most = 0;
  controller->AllReduce(&rank, &most, 1, vtkCommunicator::MAX_OP);
  return kByRank[most];
}

void SumFigures(vtkMultiProcessController* controller, fd3::Statistics& stats)
{
  std::vector<double> sums;
  for (auto field : fd3::Statistics::counts())
  {
    sums.push_back(double(stats.*field));
  }
  std::vector<double> maxima = { double(stats.maxWalkSteps) };
  for (auto field : fd3::Statistics::seconds())
  {
    maxima.push_back(stats.*field);
  }
  std::vector<double> total(sums.size()), slowest(maxima.size());
  controller->AllReduce(sums.data(), total.data(), sums.size(), vtkCommunicator::SUM_OP);
  controller->AllReduce(maxima.data(), slowest.data(), maxima.size(), vtkCommunicator::MAX_OP);
  auto sum = total.begin();
  for (auto field : fd3::Statistics::counts())
  {
    stats.*field = static_cast<std::size_t>(*sum++);
  }
  auto largest = slowest.begin();
  stats.maxWalkSteps = static_cast<std::size_t>(*largest++);
  for (auto field : fd3::Statistics::seconds())
  {
    stats.*field = *largest++;
  }
}

InputWeights ReadInputWeights(vtkDataArray* array, vtkIdType points, bool radii)
{
  InputWeights weights;
  weights.Found = array != nullptr;
  if (array)
  {
    weights.Values =
      PointWeights(array, points, radii, static_cast<std::size_t>(points), weights.Problem);
  }
  return weights;
}

DistributedRun::DistributedRun(vtkMultiProcessController* controller, int threads)
  : Ranks(controller), Threads(threads), Exchange(this->Ranks)
{}

bool DistributedRun::Redistribute(
  vtkDataSet* input, vtkPoints* points, const InputWeights& weights, vtkDataArray* cutBy)
{
  const vtkIdType count = input ? input->GetNumberOfPoints() : 0;
  std::vector<vtkIdType> counts(this->Ranks.Size);
  this->Ranks.Controller->AllGather(&count, counts.data(), 1);
  const vtkIdType firstId =
    std::accumulate(counts.begin(), counts.begin() + this->Ranks.Rank, vtkIdType(0));
  this->InputPoints = std::accumulate(counts.begin(), counts.end(), vtkIdType(0));
  int type = count > 0 ? points->GetDataType() : 0, widest = 0; // as the one-process output's
  this->Ranks.Controller->AllReduce(&type, &widest, 1, vtkCommunicator::MAX_OP);
  this->PointType = widest > 0 ? widest : VTK_DOUBLE;
  int found = weights.Found, anyFound = 0;
  this->Ranks.Controller->AllReduce(&found, &anyFound, 1, vtkCommunicator::MAX_OP);
  this->Weighted = anyFound != 0;

  vtkSmartPointer<vtkPointData> data;
  std::vector<vtkIdType> finite, nonFinite;
  if (!this->Ranks.Local([&] {
        if (!weights.Problem.empty())
        {
          throw std::runtime_error(weights.Problem);
        }
        if (this->Weighted && count > 0 && !weights.Found)
        {
          throw std::runtime_error("the weights array is missing from the input on rank " +
            std::to_string(this->Ranks.Rank));
        }
        data = InputData(input, count, firstId, this->Weighted ? &weights.Values : nullptr);
        ForEachPoint(points->GetData(), [&](vtkIdType i, const double x[3]) {
          (fd3::isFinite(x) ? finite : nonFinite).push_back(i);
        });
        return true;
      }))
  {
    return false;
  }
  Received parts;
  if (!this->SpreadFinite(points->GetData(), cutBy, data, finite, parts))
  {
    return false;
  }
  return this->Ranks.Local([&] {
    this->Gather(points->GetData(), data, nonFinite, parts);
    if (this->Weighted)
    {
      this->TakeWeights({ this->Own.Data }, false); // the halo sends them on
    }
    return true;
  });
}

bool DistributedRun::ChooseFrame(
  const std::function<std::vector<double>(const fd3::Bounds&)>& later)
{
  const Coordinates& xyz = this->Own.Xyz;
  fd3::Bounds box;
  if (!this->Ranks.Local([&] {
        box = fd3::finiteBounds(xyz.data(), this->Own.Finite, this->Threads);
        this->Boxes.assign(this->Ranks.Size, fd3::Bounds());
        return true;
      }))
  {
    return false;
  }
  this->Ranks.Controller->AllGather(box.lo, this->Boxes[0].lo, 6);
  this->GlobalBounds = fd3::Bounds();
  for (const fd3::Bounds& b : this->Boxes)
  {
    this->GlobalBounds.include(b);
  }
  this->Diagonal = this->GlobalBounds.diagonal();
  const std::vector<double> more = later ? later(this->GlobalBounds) : std::vector<double>();
  fd3::Bounds framed = this->GlobalBounds;
  for (std::size_t i = 0; i < more.size(); i += 3)
  {
    framed.include(&more[i]);
  }
  bool exact[3] = { true, true, true };
  fd3::checkShifts(xyz.data(), this->Own.Count, framed, exact);
  fd3::checkShifts(more.data(), more.size() / 3, framed, exact);
  int local[3] = { exact[0], exact[1], exact[2] }, global[3];
  this->Ranks.Controller->AllReduce(local, global, 3, vtkCommunicator::MIN_OP);
  for (int a = 0; a < 3; ++a)
  {
    exact[a] = global[a] != 0;
  }
  const fd3::Frame frame = fd3::frameFor(framed, exact);
  int fits = fd3::fitsFrame(frame, xyz.data(), this->Own.Count) &&
    fd3::fitsFrame(frame, more.data(), more.size() / 3) &&
    fd3::weightsFitFrame(frame, this->Weights.data(), this->Weights.size()),
      allFit = 0;
  this->Ranks.Controller->AllReduce(&fits, &allFit, 1, vtkCommunicator::MIN_OP);
  this->Frame = allFit ? frame : fd3::identityFrame(framed);
  if (this->Weighted)
  {
    double heaviest = -HUGE_VAL;
    for (const double w : this->Weights)
    {
      heaviest = std::isfinite(w) ? std::max(heaviest, w) : heaviest;
    }
    this->Ranks.Controller->AllReduce(&heaviest, &this->Heaviest, 1, vtkCommunicator::MAX_OP);
  }
  return true;
}

bool DistributedRun::Triangulate(const fd3::Options& options)
{
  const auto start = std::chrono::steady_clock::now();
  const bool done = this->Ranks.Local([&] {
    this->Mesh = std::make_unique<fd3::IncrementalDelaunay>(std::move(this->Own.Xyz), options,
      this->Frame, GhostRoom(this->Own.Count), this->WeightsOrNull());
    return this->Mesh->status() != fd3::Status::Aborted;
  });
  this->MeshSeconds = SecondsSince(start);
  return done;
}

bool DistributedRun::ExchangeHalo()
{
  std::vector<std::vector<std::uint32_t>> halo;
  std::vector<std::vector<double>> xyz;
  const bool meshed = this->Mesh->status() == fd3::Status::Ok;
  if (!this->Ranks.Local([&] {
        halo =
          meshed ? this->Mesh->haloVertices(this->OtherBoxes(), this->Heaviest) : this->AllToAll();
        xyz = meshed ? this->Mesh->points(halo) : std::vector<std::vector<double>>();
        return true;
      }))
  {
    return false;
  }
  // With no tetrahedron, a rank sends all its points to every other: each part is made as it
  // is sent.
  return this->Exchange.Send(
    NonEmpty(halo),
    [&](int r) {
      return this->HaloPart(halo[r], meshed ? xyz[r] : this->Mesh->points({ halo[r] })[0]);
    },
    this->Ghosts);
}

bool DistributedRun::AddGhosts()
{
  const auto start = std::chrono::steady_clock::now();
  return this->AddGhosts([&](fd3::IncrementalDelaunay& mesh, Coordinates& xyz) {
    this->Result = mesh.release(xyz);
    if (this->Result.status == fd3::Status::CheckFailed)
    {
      throw std::runtime_error(std::string("the kernel's mesh check failed (a bug; please report "
                                           "it with the input): ") +
        this->Result.checkReport);
    }
    this->Result.stats.secondsTotal = this->MeshSeconds + SecondsSince(start);
    return this->Result.status != fd3::Status::Aborted;
  });
}

bool DistributedRun::AddGhosts(
  const std::function<bool(fd3::IncrementalDelaunay&, Coordinates&)>& finish)
{
  return this->Ranks.Local([&] {
    Coordinates ghostXyz;
    std::vector<vtkPointData*> ghostData;
    for (const auto& part : this->Ghosts.Parts)
    {
      AppendPoints(part->GetPoints()->GetData(), ghostXyz);
      ghostData.push_back(part->GetPointData());
    }
    const std::size_t own = this->Weights.size();
    if (this->Weighted) // every rank has sent its halo: the weights leave the point data
    {
      this->TakeWeights(ghostData, true);
      this->Own.Data->RemoveArray(kWeights);
    }
    const double* weights = this->WeightsOrNull();
    this->Mesh->add(ghostXyz.data(), ghostXyz.size() / 3, weights ? weights + own : nullptr);
    Coordinates().swap(ghostXyz); // the mesh holds them
    const bool finished = finish(*this->Mesh, this->Xyz);
    this->Mesh.reset();
    // Made after the release, which gives back most of the mesh.
    this->Owner.assign(this->Own.Count, this->Ranks.Rank);
    for (std::size_t k = 0; k < this->Ghosts.Parts.size(); ++k)
    {
      this->Owner.insert(this->Owner.end(),
        static_cast<std::size_t>(this->Ghosts.Parts[k]->GetNumberOfPoints()),
        this->Ghosts.Senders[k]);
    }
    return finished;
  });
}

fd3::Statistics DistributedRun::GlobalFigures(fd3::Status& status)
{
  RankFigures figures;
  figures.Stats = this->Result.stats;
  figures.MeshInsertions = double(this->Result.stats.insertedPoints);
  figures.Ghosts = double(this->Xyz.size() / 3 - this->Own.Count);
  this->CountOwned(figures.Stats);
  figures.Reduce(this->Ranks.Controller);
  status = StatusOfAllRanks(this->Ranks.Controller, this->Result.status);
  this->GhostPoints = static_cast<vtkIdType>(figures.Ghosts);
  figures.Stats.inputPoints = static_cast<std::size_t>(this->InputPoints);
  return figures.Stats;
}

std::vector<vtkIdType> DistributedRun::InputIds() const
{
  std::vector<vtkIdType> ids;
  ids.reserve(this->Xyz.size() / 3);
  std::vector<vtkPointData*> parts{ this->Own.Data };
  for (const auto& ghosts : this->Ghosts.Parts)
  {
    parts.push_back(ghosts->GetPointData());
  }
  for (vtkPointData* part : parts)
  {
    vtkDataArray* inputIds = part->GetArray(kInputIds);
    for (vtkIdType i = 0; i < part->GetNumberOfTuples(); ++i)
    {
      ids.push_back(static_cast<vtkIdType>(inputIds->GetComponent(i, 0)));
    }
  }
  return ids;
}

const double* DistributedRun::WeightsOrNull() const
{
  static const double none = 0;
  return !this->Weighted ? nullptr : this->Weights.empty() ? &none : this->Weights.data();
}

void DistributedRun::TakeWeights(const std::vector<vtkPointData*>& parts, bool remove)
{
  for (vtkPointData* part : parts)
  {
    vtkDataArray* weights = part->GetArray(kWeights);
    if (!weights)
    {
      throw std::logic_error("points came without their weights");
    }
    for (vtkIdType i = 0; i < weights->GetNumberOfTuples(); ++i)
    {
      this->Weights.push_back(weights->GetComponent(i, 0));
    }
    if (remove)
    {
      part->RemoveArray(kWeights);
    }
  }
}

bool DistributedRun::Owns(const std::uint32_t* ids, int size) const
{
  // Nearly always one rank owns every vertex, and their order does not matter.
  const int owner = this->Owner[ids[0]];
  if (std::all_of(ids + 1, ids + size, [&](std::uint32_t v) { return this->Owner[v] == owner; }))
  {
    return owner == this->Ranks.Rank;
  }
  const std::uint32_t* smallest =
    std::min_element(ids, ids + size, [this](std::uint32_t a, std::uint32_t b) {
      return std::lexicographical_compare(
        &this->Xyz[3 * a], &this->Xyz[3 * a + 3], &this->Xyz[3 * b], &this->Xyz[3 * b + 3]);
    });
  return this->Owner[*smallest] == this->Ranks.Rank;
}

void DistributedRun::SetOutputPoints(vtkUnstructuredGrid* output)
{
  std::vector<vtkIdType> ghostId(this->Xyz.size() / 3 - this->Own.Count, -1);
  OnCellIds(output->GetCells(), MarkIdsFrom{}, this->Own.Count, ghostId);
  vtkIdType next = static_cast<vtkIdType>(this->Own.Count);
  for (vtkIdType& id : ghostId)
  {
    id = id == 0 ? next++ : -1;
  }
  OnCellIds(output->GetCells(), RenumberIdsFrom{}, this->Own.Count, ghostId);

  vtkNew<vtkPoints> points;
  points->SetDataType(this->PointType);
  points->SetNumberOfPoints(next);
  vtkDataArray* coordinates = points->GetData();
  for (std::size_t i = 0; i < this->Own.Count; ++i)
  {
    coordinates->SetTuple(static_cast<vtkIdType>(i), &this->Xyz[3 * i]);
  }
  for (std::size_t g = 0; g < ghostId.size(); ++g)
  {
    if (ghostId[g] >= 0)
    {
      coordinates->SetTuple(ghostId[g], &this->Xyz[3 * (this->Own.Count + g)]);
    }
  }
  output->SetPoints(points);
  this->SetOutputPointData(output, ghostId);
}

bool DistributedRun::SpreadFinite(vtkDataArray* coordinates, vtkDataArray* cutBy,
  vtkPointData* data, std::vector<vtkIdType>& finite, Received& parts)
{
  int mine = !finite.empty(), any = 0;
  this->Ranks.Controller->AllReduce(&mine, &any, 1, vtkCommunicator::MAX_OP);
  SpaceCuts cuts;
  vtkDataArray* places = cutBy ? cutBy : coordinates;
  if (!any || !this->Exchange.BalancedCuts(places, finite, cuts))
  {
    return !any;
  }
  std::vector<std::vector<vtkIdType>> lists(this->Ranks.Size);
  if (!this->Ranks.Local([&] {
        ForEachPoint(places, [&](vtkIdType i, const double x[3]) {
          if (fd3::isFinite(x))
          {
            lists[cuts.RankOf(x)].push_back(i);
          }
        });
        std::vector<vtkIdType>().swap(finite);
        return true;
      }))
  {
    return false;
  }
  const int type = this->PointType;
  if (!this->Exchange.Send(
        NonEmpty(lists), [&](int r) { return Subset(coordinates, data, lists[r], type); }, parts))
  {
    return false;
  }
  return this->Ranks.Local([&] {
    const int rank = this->Ranks.Rank;
    if (!lists[rank].empty()) // in rank order
    {
      const auto at =
        std::upper_bound(parts.Senders.begin(), parts.Senders.end(), rank) - parts.Senders.begin();
      parts.Parts.insert(parts.Parts.begin() + at, Subset(coordinates, data, lists[rank], type));
      parts.Senders.insert(parts.Senders.begin() + at, rank);
    }
    return true;
  });
}

void DistributedRun::Gather(vtkDataArray* coordinates, vtkPointData* data,
  const std::vector<vtkIdType>& nonFinite, Received& parts)
{
  this->Own.Finite = 0;
  for (const auto& part : parts.Parts)
  {
    this->Own.Finite += static_cast<std::size_t>(part->GetNumberOfPoints());
  }
  if (!nonFinite.empty() || parts.Parts.empty())
  {
    parts.Parts.push_back(Subset(coordinates, data, nonFinite, this->PointType));
  }
  this->Own.Count = this->Own.Finite + nonFinite.size();
  this->Own.Xyz.reserve(3 * (this->Own.Count + GhostRoom(this->Own.Count)));
  std::vector<vtkPointData*> partData;
  for (const auto& part : parts.Parts)
  {
    AppendPoints(part->GetPoints()->GetData(), this->Own.Xyz);
    partData.push_back(part->GetPointData());
  }
  this->Own.Data = GatherPointData(partData);
}

std::vector<fd3::Bounds> DistributedRun::OtherBoxes() const
{
  std::vector<fd3::Bounds> others = this->Boxes;
  others[this->Ranks.Rank] = fd3::Bounds();
  return others;
}

std::vector<std::vector<std::uint32_t>> DistributedRun::AllToAll() const
{
  std::vector<std::vector<std::uint32_t>> halo(this->Ranks.Size);
  for (int r = 0; r < this->Ranks.Size; ++r)
  {
    if (r != this->Ranks.Rank)
    {
      halo[r].resize(this->Own.Finite);
      std::iota(halo[r].begin(), halo[r].end(), 0u);
    }
  }
  return halo;
}

vtkSmartPointer<vtkPolyData> DistributedRun::HaloPart(
  const std::vector<std::uint32_t>& halo, const std::vector<double>& xyz) const
{
  vtkNew<vtkPoints> points;
  points->SetDataType(this->PointType);
  points->SetNumberOfPoints(static_cast<vtkIdType>(halo.size()));
  for (std::size_t k = 0; k < halo.size(); ++k)
  {
    points->SetPoint(static_cast<vtkIdType>(k), &xyz[3 * k]);
  }
  return WithPointData(points, this->Own.Data, IdList(halo));
}

void DistributedRun::CountOwned(fd3::Statistics& stats) const
{
  stats.inputPoints = stats.insertedPoints = stats.duplicatesMerged = 0;
  stats.closePointsSkipped = stats.tetrahedra = stats.hiddenPoints = 0;
  for (std::size_t t = 0; t < this->Result.numberOfTetrahedra(); ++t)
  {
    stats.tetrahedra += this->Owns(this->Result.tetrahedra.data() + 4 * t, 4);
  }
  const std::vector<std::uint32_t>& hidden = this->Result.hidden; // ascending
  auto nextHidden = hidden.begin();
  for (std::size_t k = 0; k < this->Own.Count && this->Result.status == fd3::Status::Ok; ++k)
  {
    const std::uint32_t v = this->Result.representative[k];
    const bool isHidden = nextHidden != hidden.end() && *nextHidden == k;
    nextHidden += isHidden;
    stats.hiddenPoints += isHidden;
    stats.insertedPoints += v == k && !isHidden;
    if (v != k && v != fd3::kNoPoint)
    {
      const bool same = std::equal(&this->Xyz[3 * k], &this->Xyz[3 * k + 3], &this->Xyz[3 * v]);
      (same ? stats.duplicatesMerged : stats.closePointsSkipped) += 1;
    }
  }
}

void DistributedRun::SetOutputPointData(
  vtkUnstructuredGrid* output, const std::vector<vtkIdType>& ghostId)
{
  std::vector<vtkSmartPointer<vtkPolyData>> used;
  std::vector<vtkPointData*> parts{ this->Own.Data };
  std::size_t g = 0;
  for (const auto& ghosts : this->Ghosts.Parts)
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
  const vtkIdType count = output->GetNumberOfPoints();
  vtkNew<vtkUnsignedCharArray> ghostType;
  ghostType->SetName(vtkDataSetAttributes::GhostArrayName());
  ghostType->SetNumberOfValues(count);
  std::fill_n(ghostType->GetPointer(0), this->Own.Count, 0);
  std::fill(ghostType->GetPointer(0) + this->Own.Count, ghostType->GetPointer(0) + count,
    static_cast<unsigned char>(vtkDataSetAttributes::DUPLICATEPOINT));
  data->AddArray(ghostType);
}
} // namespace fd3vtk
