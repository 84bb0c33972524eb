/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkPFastDelaunay3D.h"

#include "vtkAppendFilter.h"
#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCommunicator.h"
#include "vtkDIYDataExchanger.h"
#include "vtkDataArrayRange.h"
#include "vtkDistributedPointCloudFilter.h"
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

#include "fd3/Delaunay.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <exception>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPFastDelaunay3D);
vtkCxxSetObjectMacro(vtkPFastDelaunay3D, Controller, vtkMultiProcessController);

namespace
{
constexpr const char* kInputIds = "GlobalIds";

/// The points `ids` of `source`, with their point data.
vtkSmartPointer<vtkPolyData> Subset(vtkPointSet* source, const std::vector<vtkIdType>& ids)
{
  vtkNew<vtkIdList> from, to;
  from->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  to->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  for (std::size_t k = 0; k < ids.size(); ++k)
  {
    from->SetId(static_cast<vtkIdType>(k), ids[k]);
    to->SetId(static_cast<vtkIdType>(k), static_cast<vtkIdType>(k));
  }
  vtkNew<vtkPoints> points;
  points->SetDataType(source->GetPoints()->GetDataType());
  source->GetPoints()->GetPoints(from, points);
  auto subset = vtkSmartPointer<vtkPolyData>::New();
  subset->SetPoints(points);
  subset->GetPointData()->CopyAllocate(source->GetPointData(), from->GetNumberOfIds());
  subset->GetPointData()->CopyData(source->GetPointData(), from, to);
  return subset;
}

/// Appends point sets (points and the point data they all have), in order.
vtkSmartPointer<vtkUnstructuredGrid> Concatenate(const std::vector<vtkSmartPointer<vtkPointSet>>& parts)
{
  vtkNew<vtkAppendFilter> append;
  append->MergePointsOff();
  for (const auto& part : parts)
  {
    append->AddInputData(part);
  }
  append->Update();
  return append->GetOutput();
}

/// Replaces every point id of the cells by map[id].
struct RenumberIds
{
  template <typename Array>
  void operator()(Array* ids, const std::vector<vtkIdType>& map) const
  {
    using Id = vtk::GetAPIType<Array>;
    for (auto&& id : vtk::DataArrayValueRange<1>(ids))
    {
      id = static_cast<Id>(map[static_cast<std::size_t>(id)]);
    }
  }
};

/// One execution across the ranks, step by step (see the class documentation).
class DistributedRun
{
public:
  DistributedRun(vtkMultiProcessController* controller)
    : Controller(controller)
    , Rank(controller->GetLocalProcessId())
    , Ranks(controller->GetNumberOfProcesses())
  {
  }

  /// Step 1: the finite points spread over the ranks by space, this rank's non-finite ones after
  /// them (nothing to triangulate, but they stay in the output as unused points). `points`: the
  /// input's, in the output's precision. False when no rank has a point.
  bool Distribute(vtkDataSet* input, vtkPoints* points)
  {
    const vtkIdType count = input ? input->GetNumberOfPoints() : 0;
    std::vector<vtkIdType> counts(this->Ranks);
    this->Controller->AllGather(&count, counts.data(), 1);
    const vtkIdType firstId = std::accumulate(counts.begin(), counts.begin() + this->Rank, vtkIdType(0));
    this->InputPoints = std::accumulate(counts.begin(), counts.end(), vtkIdType(0));

    auto all = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkIdTypeArray> inputIds;
    inputIds->SetName(kInputIds);
    inputIds->SetNumberOfValues(count);
    std::vector<vtkIdType> finite, nonFinite;
    double x[3];
    for (vtkIdType i = 0; i < count; ++i)
    {
      points->GetPoint(i, x);
      inputIds->SetValue(i, firstId + i);
      (fd3::isFinite(x) ? finite : nonFinite).push_back(i);
    }
    all->SetPoints(points);
    if (input)
    {
      all->GetPointData()->ShallowCopy(input->GetPointData());
      all->GetPointData()->RemoveArray(vtkDataSetAttributes::GhostArrayName());
    }
    all->GetPointData()->AddArray(inputIds);
    this->Own = all;
    this->FiniteCount = 0;
    vtkIdType finiteCount = static_cast<vtkIdType>(finite.size()), finiteTotal = 0;
    this->Controller->AllReduce(&finiteCount, &finiteTotal, 1, vtkCommunicator::SUM_OP);
    if (finiteTotal == 0)
    {
      return this->InputPoints > 0;
    }
    vtkNew<vtkDistributedPointCloudFilter> spread;
    spread->SetController(this->Controller);
    spread->SetInputData(nonFinite.empty() ? all.Get() : Subset(all, finite).Get());
    spread->Update();
    this->Own = spread->GetOutput();
    this->FiniteCount = static_cast<std::size_t>(this->Own->GetNumberOfPoints());
    if (!nonFinite.empty())
    {
      this->Own = Concatenate({ this->Own, Subset(all, nonFinite) });
    }
    if (!this->Own->GetPoints())
    {
      this->Own->SetPoints(vtkNew<vtkPoints>());
    }
    return true;
  }

  /// The ghost points that room is made for up front, in Xyz and in the kernel's vertex records: a
  /// rank receives a few percent of its own count at 1M points a rank, more on small ones. Growing
  /// either later would copy it, and under MPI the copy's source stays resident (measured with
  /// Open MPI at 4M points on 2 ranks: the 48 MB of Xyz freed after growing kept the rank's
  /// resident size 46 MB up to its peak).
  std::size_t GhostRoom() const
  {
    return static_cast<std::size_t>(this->Own->GetNumberOfPoints()) / 4 + 1024;
  }

  /// Step 2: one exact frame for every rank, from the global bounds and the shifts that are
  /// exact on every rank. ownXyz, ownBounds: the coordinates of Own as doubles, the bounds of its
  /// finite points.
  fd3::Frame Frame(const double* ownXyz, const double ownBounds[6])
  {
    this->OwnCount = static_cast<std::size_t>(this->Own->GetNumberOfPoints());
    if (this->Xyz.data() != ownXyz)
    {
      this->Xyz.assign(ownXyz, ownXyz + 3 * this->OwnCount);
    }
    fd3::Bounds box;
    std::copy_n(ownBounds, 6, box.begin());
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
    const double centre[3] = { lo[0] + (hi[0] - lo[0]) / 2, lo[1] + (hi[1] - lo[1]) / 2,
      lo[2] + (hi[2] - lo[2]) / 2 };
    bool exact[3] = { true, true, true };
    fd3::checkShifts(this->Xyz.data(), this->OwnCount, centre, exact);
    int local[3] = { exact[0], exact[1], exact[2] }, global[3];
    this->Controller->AllReduce(local, global, 3, vtkCommunicator::MIN_OP);
    for (int a = 0; a < 3; ++a)
    {
      exact[a] = global[a] != 0;
    }
    this->Diagonal = std::sqrt(
      std::pow(hi[0] - lo[0], 2) + std::pow(hi[1] - lo[1], 2) + std::pow(hi[2] - lo[2], 2));
    return fd3::frameFor(lo, hi, exact);
  }

  /// Step 3: this rank's points tetrahedralized, and the halo of every other rank sent to it.
  void Exchange(fd3::Tetrahedralization& mesh)
  {
    std::vector<fd3::Bounds> others = this->Boxes;
    others[this->Rank] = { 1, -1, 1, -1, 1, -1 };
    std::vector<std::vector<std::uint32_t>> halo = mesh.haloVertices(this->Xyz.data(), others);
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
    std::vector<vtkSmartPointer<vtkDataSet>> sent;
    std::vector<int> sendCounts(this->Ranks, 0);
    for (int r = 0; r < this->Ranks; ++r)
    {
      if (!halo[r].empty())
      {
        sent.push_back(Subset(this->Own, std::vector<vtkIdType>(halo[r].begin(), halo[r].end())));
        sendCounts[r] = 1;
      }
    }
    std::vector<vtkSmartPointer<vtkDataSet>> received;
    std::vector<int> receiveCounts;
    vtkNew<vtkDIYDataExchanger> exchanger;
    exchanger->SetController(this->Controller);
    exchanger->AllToAll(sent, sendCounts, received, receiveCounts);
    std::size_t next = 0;
    for (int r = 0; r < this->Ranks; ++r)
    {
      for (int k = 0; k < receiveCounts[r]; ++k, ++next)
      {
        auto* ghosts = vtkPointSet::SafeDownCast(received[next]);
        if (ghosts && ghosts->GetNumberOfPoints() > 0)
        {
          this->Ghosts.emplace_back(ghosts);
          this->GhostSenders.push_back(r);
        }
      }
    }
  }

  /// Step 4: the received points added to this rank's mesh; the owner of every vertex.
  fd3::Triangulation AddGhosts(fd3::Tetrahedralization& mesh)
  {
    const std::size_t ownValues = this->Xyz.size();
    std::size_t received = 0;
    for (const auto& ghosts : this->Ghosts)
    {
      received += static_cast<std::size_t>(ghosts->GetNumberOfPoints());
    }
    this->Xyz.reserve(ownValues + 3 * received); // beyond GhostRoom(), exactly: the peak is near
    this->Holder.reserve(this->OwnCount + received);
    for (const auto& ghosts : this->Ghosts)
    {
      double x[3];
      for (vtkIdType i = 0; i < ghosts->GetNumberOfPoints(); ++i)
      {
        ghosts->GetPoint(i, x);
        this->Xyz.insert(this->Xyz.end(), x, x + 3);
        this->Holder.push_back(this->GhostSenders[&ghosts - this->Ghosts.data()]);
      }
    }
    mesh.add(this->Xyz.data() + ownValues, (this->Xyz.size() - ownValues) / 3);
    fd3::Triangulation result = mesh.release();
    const std::size_t count = this->Xyz.size() / 3;
    std::vector<int> copies(count, INT_MAX);
    this->VertexCell.assign(count, false);
    this->Holder.insert(this->Holder.begin(), this->OwnCount, this->Rank);
    for (std::size_t k = 0; k < count && result.status == fd3::Status::Ok; ++k)
    {
      const std::uint32_t v = result.representative[k];
      if (v != fd3::kNoPoint && this->SamePosition(k, v))
      {
        copies[v] = std::min(copies[v], this->Holder[k]);
      }
    }
    this->Holder.swap(copies);
    return result;
  }

  /// Whether this rank owns the simplex: it holds the lowest copy of its smallest vertex. A
  /// vertex cell (a point on no other cell of the alpha shape, or a duplicate) goes with the
  /// point itself: every input point is one rank's own.
  bool Owns(const std::uint32_t* ids, int size)
  {
    if (size == 1)
    {
      this->VertexCell[ids[0]] = true;
      return ids[0] < this->OwnCount;
    }
    const std::uint32_t* smallest = std::min_element(ids, ids + size, [this](std::uint32_t a, std::uint32_t b) {
      return std::lexicographical_compare(&this->Xyz[3 * a], &this->Xyz[3 * a + 3], &this->Xyz[3 * b],
        &this->Xyz[3 * b + 3]);
    });
    return this->Holder[*smallest] == this->Rank;
  }

  /// The vertex cells the serial filter has and the alpha complex of this rank cannot know of:
  /// where copies of one position lie on several ranks and the position is on a cell, one copy
  /// is a vertex of that cell and the others are duplicates, each with its vertex cell. Here the
  /// lowest rank's copy is the vertex; the copies on other ranks get their vertex cells.
  void AddDuplicateVertexCells(vtkUnstructuredGrid* output, const fd3::Triangulation& result)
  {
    for (std::size_t v = 0; v < this->OwnCount; ++v)
    {
      if (result.representative[v] == v && this->Holder[v] != this->Rank && !this->VertexCell[v])
      {
        const vtkIdType id = static_cast<vtkIdType>(v);
        output->InsertNextCell(VTK_VERTEX, 1, &id);
      }
    }
  }

  /// Step 5: the output's points: this rank's own, then the received ones its cells use (as
  /// duplicate points), with the cells' ids renumbered to match.
  void SetOutputPoints(vtkUnstructuredGrid* output)
  {
    const std::size_t count = this->Xyz.size() / 3;
    std::vector<vtkIdType> newId(count, -1);
    std::iota(newId.begin(), newId.begin() + this->OwnCount, vtkIdType(0));
    for (vtkIdType id : vtk::DataArrayValueRange<1>(output->GetCells()->GetConnectivityArray()))
    {
      if (static_cast<std::size_t>(id) >= this->OwnCount)
      {
        newId[static_cast<std::size_t>(id)] = 0; // used, numbered below
      }
    }
    std::vector<vtkSmartPointer<vtkPointSet>> parts{ this->Own };
    vtkIdType next = static_cast<vtkIdType>(this->OwnCount);
    std::size_t ghost = this->OwnCount;
    for (const auto& ghosts : this->Ghosts)
    {
      std::vector<vtkIdType> used;
      for (vtkIdType i = 0; i < ghosts->GetNumberOfPoints(); ++i, ++ghost)
      {
        if (newId[ghost] == 0)
        {
          used.push_back(i);
          newId[ghost] = next++;
        }
      }
      parts.push_back(Subset(ghosts, used));
    }
    using Ids = vtkArrayDispatch::DispatchByArray<vtkCellArray::StorageArrayList>;
    vtkDataArray* connectivity = output->GetCells()->GetConnectivityArray();
    if (!Ids::Execute(connectivity, RenumberIds{}, newId))
    {
      RenumberIds{}(connectivity, newId);
    }
    vtkSmartPointer<vtkUnstructuredGrid> points = Concatenate(parts);
    output->SetPoints(points->GetPoints());
    output->GetPointData()->ShallowCopy(points->GetPointData());
    output->GetPointData()->SetGlobalIds(output->GetPointData()->GetArray(kInputIds));
    vtkNew<vtkUnsignedCharArray> ghostType;
    ghostType->SetName(vtkDataSetAttributes::GhostArrayName());
    ghostType->SetNumberOfValues(next);
    ghostType->FillValue(0);
    for (vtkIdType i = static_cast<vtkIdType>(this->OwnCount); i < next; ++i)
    {
      ghostType->SetValue(i, vtkDataSetAttributes::DUPLICATEPOINT);
    }
    output->GetPointData()->AddArray(ghostType);
  }

  /// The figures of all ranks: counts summed (each vertex counted by its owner), times the
  /// slowest rank's.
  fd3::Statistics GlobalFigures(const fd3::Triangulation& result, std::size_t ownedTetrahedra)
  {
    const fd3::Statistics& s = result.stats;
    std::size_t inserted = 0, skipped = 0;
    for (std::size_t k = 0; k < this->OwnCount && result.status == fd3::Status::Ok; ++k)
    {
      const std::uint32_t v = result.representative[k];
      inserted += v == k && this->Holder[k] == this->Rank;
      skipped += v != k && v != fd3::kNoPoint && !this->SamePosition(k, v);
    }
    std::array<double, 9> sums = { double(s.nonFinitePoints), double(inserted), double(skipped),
      double(ownedTetrahedra), double(s.walkSteps), double(s.cavityTetrahedra),
      double(s.underflowRisks), double(s.insertedPoints), double(this->Xyz.size() / 3 - this->OwnCount) },
                           total;
    std::array<double, 7> maxima = { double(s.maxWalkSteps), s.secondsSort, s.secondsLocate,
      s.secondsCavity, s.secondsFill, s.secondsOutput, s.secondsTotal },
                          slowest;
    this->Controller->AllReduce(sums.data(), total.data(), sums.size(), vtkCommunicator::SUM_OP);
    this->Controller->AllReduce(maxima.data(), slowest.data(), maxima.size(), vtkCommunicator::MAX_OP);
    fd3::Statistics global;
    global.inputPoints = static_cast<std::size_t>(this->InputPoints);
    global.nonFinitePoints = static_cast<std::size_t>(total[0]);
    global.insertedPoints = static_cast<std::size_t>(total[1]);
    global.closePointsSkipped = static_cast<std::size_t>(total[2]);
    global.duplicatesMerged = global.inputPoints - global.insertedPoints - global.closePointsSkipped -
      global.nonFinitePoints;
    global.tetrahedra = static_cast<std::size_t>(total[3]);
    // Walks and cavities of ghost insertions count too: that is the work done.
    global.walkSteps = static_cast<std::size_t>(total[4] * total[1] / std::max(total[7], 1.0));
    global.cavityTetrahedra = static_cast<std::size_t>(total[5] * total[1] / std::max(total[7], 1.0));
    global.underflowRisks = static_cast<std::size_t>(total[6]);
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
    std::unique_ptr<fd3::Tetrahedralization> mesh;
    auto start = Clock::now();
    double seconds = 0; // meshing only: the exchange is left out
    try
    {
      mesh = std::make_unique<fd3::Tetrahedralization>(
        this->Xyz.data(), this->OwnCount, options, frame, this->GhostRoom());
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
      result.stats.secondsTotal = seconds + std::chrono::duration<double>(Clock::now() - start).count();
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
      return s == fd3::Status::Ok ? 3 : s == fd3::Status::Degenerate ? 2 : s == fd3::Status::TooFewPoints ? 1 : 0;
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
  vtkSmartPointer<vtkPointSet> Own;       ///< this rank's points: finite ones by space, then its NaN/Inf
  std::size_t OwnCount = 0;
  std::size_t FiniteCount = 0;            ///< Own's first points, the finite ones
  std::vector<double> Xyz;                ///< own points, then the received ones
  std::vector<fd3::Bounds> Boxes;         ///< every rank's bounds
  std::vector<vtkSmartPointer<vtkPointSet>> Ghosts; ///< received, one set per sender
  std::vector<int> GhostSenders;
  std::vector<int> Holder; ///< per vertex: the lowest rank holding its position
  std::vector<bool> VertexCell; ///< per point: the alpha shape has its vertex cell
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
  if (!vtkMPIController::SafeDownCast(this->Controller) || this->Controller->GetNumberOfProcesses() < 2)
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
    return 1;
  }
  double ownBounds[6];
  BoundsOfFinitePoints(run.Own, ownBounds);
  // Here, not in Distribute(): its scratch is freed by now (rank 0's peak at 4M points on 2
  // ranks, 969 MB, is 978 MB when Xyz is reserved before it is).
  run.Xyz.reserve(3 * (static_cast<std::size_t>(run.Own->GetNumberOfPoints()) + run.GhostRoom()));
  const fd3::Frame frame = run.Frame(CoordinatesAsDoubles(run.Own->GetPoints(), run.Xyz), ownBounds);
  fd3::Triangulation result;
  std::string failure;
  const bool done = run.Triangulate(this->KernelOptions(run.Diagonal), frame, result, failure);
  if (!failure.empty())
  {
    vtkErrorMacro("Triangulation failed: " << failure << "; the output is empty");
  }
  if (!done)
  {
    return 1;
  }

  const auto outputStart = std::chrono::steady_clock::now();
  const fd3::Status status = run.GlobalStatus(result.status);
  std::size_t owned = 0;
  auto owns = [&run](const std::uint32_t* ids, int size) { return run.Owns(ids, size); };
  for (std::size_t t = 0; t < result.numberOfTetrahedra(); ++t)
  {
    owned += owns(result.tetrahedra.data() + 4 * t, 4);
  }
  fd3::Statistics figures = run.GlobalFigures(result, owned);
  this->NumberOfGhostPoints = run.GhostPoints;
  if (status == fd3::Status::Ok && result.status == fd3::Status::Ok)
  {
    this->SetOutputCells(output, run.Xyz.data(), run.Xyz.size() / 3, result, owns);
    if (this->Alpha > 0 && this->AlphaVerts)
    {
      run.AddDuplicateVertexCells(output, result);
    }
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
    output->Initialize();
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
