/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkPFastVoronoi3D.h"

#include "DistributedRun.h"
#include "FilterBox.h"
#include "FilterInput.h"
#include "GatheredPoints.h"
#include "PeriodicRun.h"

#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Voronoi.h"
#include "fd3/Workers.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <exception>
#include <string>

vtkStandardNewMacro(vtkPFastVoronoi3D);
vtkCxxSetObjectMacro(vtkPFastVoronoi3D, Controller, vtkMultiProcessController);

namespace
{
/// One rank's figures, then all ranks' together (Sum()). A rank's duplicates and non-finite
/// points are its own points' (a position is one rank's, and the halo is finite).
struct CellFigures
{
  double Cells = 0;
  double Duplicates = 0;
  double NonFinite = 0;
  double Hidden = 0;     ///< weighted: own points whose power cell is empty
  double Ghosts = 0;     ///< points received
  double OutOfRange = 0; ///< ranks whose cells span more than doubles hold

  void Sum(vtkMultiProcessController* controller)
  {
    constexpr std::array<double CellFigures::*, 6> kFields = { &CellFigures::Cells,
      &CellFigures::Duplicates, &CellFigures::NonFinite, &CellFigures::Hidden, &CellFigures::Ghosts,
      &CellFigures::OutOfRange };
    std::array<double, kFields.size()> local, total;
    for (std::size_t k = 0; k < kFields.size(); ++k)
    {
      local[k] = this->*kFields[k];
    }
    controller->AllReduce(local.data(), total.data(), local.size(), vtkCommunicator::SUM_OP);
    for (std::size_t k = 0; k < kFields.size(); ++k)
    {
      this->*kFields[k] = total[k];
    }
  }
};

/// The cells' GeneratorId: the input ids that the points brought (kInputIds, as cell data), which
/// then leave the cell data.
void SetGeneratorIds(vtkUnstructuredGrid* output)
{
  vtkCellData* cellData = output->GetCellData();
  vtkDataArray* inputIds = cellData->GetArray(fd3vtk::kInputIds);
  auto* generatorIds = vtkIdTypeArray::SafeDownCast(cellData->GetArray("GeneratorId"));
  if (!inputIds || !generatorIds) // no cells
  {
    cellData->RemoveArray(fd3vtk::kInputIds);
    return;
  }
  for (vtkIdType c = 0; c < generatorIds->GetNumberOfValues(); ++c)
  {
    generatorIds->SetValue(c, static_cast<vtkIdType>(inputIds->GetComponent(c, 0)));
  }
  cellData->RemoveArray(fd3vtk::kInputIds);
}
} // namespace

vtkPFastVoronoi3D::vtkPFastVoronoi3D()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkPFastVoronoi3D::~vtkPFastVoronoi3D()
{
  this->SetController(nullptr);
}

int vtkPFastVoronoi3D::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->NumberOfGhostPoints = 0;
  if (!fd3vtk::IsDistributed(this->Controller))
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  vtkPolyData* faces = vtkPolyData::GetData(outputVector, 1);
  output->Initialize();
  faces->Initialize();
  this->RecordFigures(0, 0, 0);
  if (fd3vtk::AnyPeriodic(this->Periodic))
  {
    if (!fd3vtk::AnyRank(this->Controller,
          fd3vtk::WeightsChosen(this) && this->GetInputArrayToProcess(0, inputVector)))
    {
      return this->PeriodicPieceCells(input, output, faces);
    }
    // Weights in a periodic box are gathered: the first rank runs them as one process does.
    vtkSmartPointer<vtkPointSet> all =
      fd3vtk::GatheredPoints(this->Controller, input, this, "No Voronoi cells: no input points");
    if (!all)
    {
      return 1;
    }
    return this->OutputCells(all,
      fd3vtk::WeightsChosen(this) ? this->GetInputArrayToProcess(0, all) : nullptr, output, faces);
  }
  const fd3vtk::InputWeights weights = fd3vtk::ReadInputWeights(
    fd3vtk::WeightsChosen(this) ? this->GetInputArrayToProcess(0, inputVector) : nullptr,
    input ? input->GetNumberOfPoints() : 0, this->WeightsAreRadii);
  vtkSmartPointer<vtkPoints> inputPoints =
    fd3vtk::PointsInPrecision(input, vtkAlgorithm::DEFAULT_PRECISION);
  const bool root = this->Controller->GetLocalProcessId() == 0;

  // The points spread by space, each rank's mesh, and the halo that completes its points' cells.
  const auto kernelStart = std::chrono::steady_clock::now();
  fd3vtk::DistributedRun run(this->Controller, fd3vtk::ThreadCount(this->NumberOfThreads));
  const bool redistributed = run.Redistribute(input, inputPoints, weights);
  if (redistributed && run.InputPoints == 0)
  {
    if (root)
    {
      vtkWarningMacro("No Voronoi cells: no input points");
    }
    return 1;
  }
  // The cells come from each rank's mesh of its points and the halo, once the far points that
  // close every cell are added: the frame holds those too.
  fd3::VoronoiOptions options = this->KernelOptions();
  const bool boxGiven = options.box.finite(); // else the points' bounds
  const auto farPoints = [&](const fd3::Bounds& global) {
    return fd3::voronoiFarPoints(global, boxGiven ? options.box : global);
  };
  fd3::Options meshOptions;
  meshOptions.threads = options.threads;
  meshOptions.computeNeighbors = false; // the cells list the stars instead
  meshOptions.progress = [this](double fraction) {
    this->UpdateProgress(0.3 * fraction);
    return !fd3vtk::AbortRequested(this);
  };
  if (!redistributed || !run.ChooseFrame(farPoints) || !run.Triangulate(meshOptions) ||
    !run.ExchangeHalo())
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed);
  }
  if (!boxGiven)
  {
    options.box = run.GlobalBounds;
  }
  options.generators = run.OwnCount();
  fd3::VoronoiCells cells;
  if (!run.AddGhosts([&](fd3::IncrementalDelaunay& mesh, fd3::Coordinates& xyz) {
        cells = fd3::voronoiCells(mesh, run.GlobalBounds, options, xyz, run.WeightsOrNull());
        return cells.status != fd3::Status::Aborted;
      }))
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed);
  }
  this->KernelSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - kernelStart).count();
  return this->OutputPieceCells(cells, run.Xyz, run.OwnData(),
    this->GenerateFaces ? run.InputIds() : std::vector<vtkIdType>(), run.OwnCount(),
    run.InputPoints, run.Weighted, options.box, output, faces);
}

int vtkPFastVoronoi3D::PeriodicPieceCells(
  vtkDataSet* input, vtkUnstructuredGrid* output, vtkPolyData* faces)
{
  vtkSmartPointer<vtkPoints> inputPoints =
    fd3vtk::PointsInPrecision(input, vtkAlgorithm::DEFAULT_PRECISION);
  const bool root = this->Controller->GetLocalProcessId() == 0;
  const fd3::VoronoiOptions options =
    this->KernelOptions(fd3vtk::GlobalFiniteBounds(this->Controller, inputPoints));
  const fd3::PeriodicBox box = fd3vtk::PeriodicBoxOf(options.box, this->Periodic);
  const std::string problem = fd3vtk::PeriodicBoxProblem(box); // alike on every rank
  if (!problem.empty())
  {
    if (root)
    {
      vtkErrorMacro("Voronoi cells failed: " << problem << "; the output is empty");
    }
    return 0;
  }

  const auto kernelStart = std::chrono::steady_clock::now();
  fd3vtk::DistributedRun run(this->Controller, options.threads);
  fd3vtk::PeriodicRun periodic(run, box);
  if (!periodic.Redistribute(input, inputPoints))
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed);
  }
  if (run.InputPoints == 0)
  {
    if (root)
    {
      vtkWarningMacro("No Voronoi cells: no input points");
    }
    return 1;
  }
  fd3::VoronoiCells cells;
  if (!periodic.Run([&](const fd3::PeriodicPiece& own, double& widerHalo) {
        cells = fd3::voronoiCellsPeriodicPiece(
          periodic.Xyz.data(), periodic.Xyz.size() / 3, box, own, widerHalo, options);
        return cells.status != fd3::Status::Aborted;
      }))
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed);
  }
  this->KernelSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - kernelStart).count();
  return this->OutputPieceCells(cells, periodic.Xyz, run.OwnData(),
    this->GenerateFaces ? std::vector<vtkIdType>(periodic.Ids.begin(), periodic.Ids.end())
                        : std::vector<vtkIdType>(),
    run.OwnCount(), run.InputPoints, false, options.box, output, faces);
}

int vtkPFastVoronoi3D::OutputPieceCells(fd3::VoronoiCells& cells, fd3::Coordinates& xyz,
  vtkPointData* ownData, const std::vector<vtkIdType>& inputIds, std::size_t own,
  vtkIdType inputPoints, bool weighted, const fd3::Bounds& box, vtkUnstructuredGrid* output,
  vtkPolyData* faces)
{
  const bool root = this->Controller->GetLocalProcessId() == 0;
  const std::size_t ghosts = xyz.size() / 3 - own;
  if (this->GeneratePolyhedra)
  {
    fd3::Coordinates().swap(xyz); // else the generators' points come from it
  }

  CellFigures figures;
  figures.Cells = double(cells.numberOfCells());
  figures.Duplicates = double(cells.stats.duplicatesMerged);
  figures.NonFinite = double(cells.stats.nonFinitePoints);
  figures.Hidden = double(cells.stats.hiddenPoints);
  figures.Ghosts = double(ghosts);
  figures.OutOfRange = cells.status == fd3::Status::OutOfRange;
  figures.Sum(this->Controller);
  this->RecordFigures(static_cast<vtkIdType>(figures.Cells),
    static_cast<vtkIdType>(figures.Duplicates), static_cast<vtkIdType>(figures.NonFinite),
    static_cast<vtkIdType>(figures.Hidden));
  this->NumberOfGhostPoints = static_cast<vtkIdType>(figures.Ghosts);
  const fd3::Status status = figures.OutOfRange > 0 ? fd3::Status::OutOfRange
    : figures.Cells > 0                             ? fd3::Status::Ok
                                                    : fd3::Status::Empty;
  const bool hasCells =
    root ? this->ReportOnInput(status, box, inputPoints, weighted) : status == fd3::Status::Ok;
  if (!hasCells)
  {
    return 1;
  }
  const auto conversionStart = std::chrono::steady_clock::now();
  fd3::Workers workers(fd3vtk::ThreadCount(this->NumberOfThreads));
  vtkSmartPointer<vtkPoints> vertices = this->SetGeometry(output, cells, xyz.data(), workers);
  this->UpdateProgress(0.9);
  AddCellData(output, cells, ownData, workers);
  SetGeneratorIds(output);
  if (this->GenerateFaces)
  {
    SetFaces(faces, cells, vertices, [&](std::uint32_t id) { return inputIds[id]; });
  }
  this->ConversionSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - conversionStart).count();
  this->AddFigures(output->GetFieldData());
  return 1;
}

int vtkPFastVoronoi3D::Stop(const std::string& failure, bool anyFailed)
{
  if (!anyFailed)
  {
    // Every rank stops as the one that was aborted, and runs again on the next update as an
    // aborted filter does; else that rank alone would, and wait for the others.
    this->SetAbortOutput(true);
    return 1;
  }
  if (!failure.empty())
  {
    vtkErrorMacro("Voronoi cells failed: " << failure << "; the output is empty");
  }
  else if (this->Controller->GetLocalProcessId() == 0)
  {
    vtkErrorMacro("Voronoi cells failed on another rank; the output is empty");
  }
  return 0;
}

void vtkPFastVoronoi3D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "NumberOfGhostPoints: " << this->NumberOfGhostPoints << "\n";
}
