/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkPFastDelaunay3D.h"

#include "DistributedRun.h"
#include "FilterBox.h"
#include "FilterCells.h"
#include "FilterInput.h"
#include "GatheredPoints.h"
#include "PeriodicRun.h"

#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include <chrono>
#include <exception>
#include <limits>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkPFastDelaunay3D);
vtkCxxSetObjectMacro(vtkPFastDelaunay3D, Controller, vtkMultiProcessController);

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
  if (!fd3vtk::IsDistributed(this->Controller))
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  output->Initialize();
  this->RecordFigures(fd3::Statistics());
  if (fd3vtk::AnyPeriodic(this->Periodic))
  {
    if (!fd3vtk::AnyRank(this->Controller,
          fd3vtk::WeightsChosen(this) && this->GetInputArrayToProcess(0, inputVector)))
    {
      return this->TriangulatePeriodicPieces(input, output);
    }
    // Weights in a periodic box are gathered: the first rank runs them as one process does.
    vtkSmartPointer<vtkPointSet> all =
      fd3vtk::GatheredPoints(this->Controller, input, this, "Cannot triangulate; no input points");
    if (!all)
    {
      return 1;
    }
    return this->TriangulatePeriodic(
      all, output, fd3vtk::WeightsChosen(this) ? this->GetInputArrayToProcess(0, all) : nullptr);
  }
  if (this->BoundingTriangulation)
  {
    vtkErrorMacro("BoundingTriangulation is not available across MPI ranks; the output is empty");
    return 1;
  }

  if (this->Locator && this->Controller->GetLocalProcessId() == 0)
  {
    vtkWarningMacro("The Locator is not used across MPI ranks: exact duplicates are merged, and "
                    "Tolerance applies");
  }
  vtkSmartPointer<vtkPoints> inputPoints =
    fd3vtk::PointsInPrecision(input, this->OutputPointsPrecision);
  vtkPointData* inputData = input ? input->GetPointData() : nullptr;
  const bool root = this->Controller->GetLocalProcessId() == 0;
  const fd3vtk::InputWeights weights = fd3vtk::ReadInputWeights(
    fd3vtk::WeightsChosen(this) ? this->GetInputArrayToProcess(0, inputVector) : nullptr,
    input ? input->GetNumberOfPoints() : 0, this->WeightsAreRadii);

  fd3vtk::DistributedRun run(this->Controller, fd3vtk::ThreadCount(this->NumberOfThreads));
  const bool redistributed = run.Redistribute(input, inputPoints, weights);
  if (redistributed && run.InputPoints == 0)
  {
    if (root)
    {
      vtkWarningMacro("Cannot triangulate; no input points");
    }
    fd3vtk::SetPointsWithoutCells(output, nullptr, nullptr);
    return 1;
  }
  if (!redistributed || !run.ChooseFrame() || !run.Triangulate(this->KernelOptions(run.Diagonal)) ||
    !run.ExchangeHalo() || !run.AddGhosts())
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed, output, inputPoints, inputData);
  }

  const auto outputStart = std::chrono::steady_clock::now();
  fd3::Status status = fd3::Status::Ok;
  fd3::Statistics figures = run.GlobalFigures(status);
  this->NumberOfGhostPoints = run.GhostPoints;
  if (root) // one report for all ranks
  {
    this->ReportOnInput(status, figures, static_cast<vtkIdType>(figures.inputPoints), run.Weighted);
  }
  if (status != fd3::Status::Ok)
  {
    this->RecordFigures(figures);
    fd3vtk::SetPointsWithoutCells(output, inputPoints, inputData);
    return 1;
  }
  try // no rank waits for this one from here on
  {
    std::vector<double> density; // of the own points, the first; before the cells take the mesh
    if (this->ComputeDensity)
    {
      density = fd3::densities(run.Xyz.data(), run.Xyz.size() / 3, run.Result);
      density.resize(run.OwnCount());
    }
    if (run.Result.status == fd3::Status::Ok)
    {
      this->SetOutputCells(output, run.Xyz.data(), run.WeightsOrNull(), run.Xyz.size() / 3,
        run.Result, [&run](const std::uint32_t* ids, int size) { return run.Owns(ids, size); });
    }
    else // a rank whose points are all NaN or Inf: they stay in its output, unused
    {
      fd3vtk::SetPointsWithoutCells(output, nullptr, nullptr);
    }
    run.SetOutputPoints(output);
    std::vector<double> converted;
    this->AddCellArrays(output, fd3vtk::CoordinatesAsDoubles(output->GetPoints(), converted));
    if (this->ComputeDensity)
    {
      AddDensity(output, density); // ghosts' stars are partial here: NaN
    }
  }
  catch (const std::exception& error)
  {
    return this->Stop(error.what(), true, output, inputPoints, inputData);
  }
  figures.secondsOutput +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - outputStart).count();
  this->RecordFigures(figures);
  this->AddFigures(output->GetFieldData());
  return 1;
}

int vtkPFastDelaunay3D::TriangulatePeriodicPieces(vtkDataSet* input, vtkUnstructuredGrid* output)
{
  vtkSmartPointer<vtkPoints> inputPoints =
    fd3vtk::PointsInPrecision(input, this->OutputPointsPrecision);
  vtkPointData* inputData = input ? input->GetPointData() : nullptr;
  const bool root = this->Controller->GetLocalProcessId() == 0;
  const fd3::Bounds bounds = fd3vtk::GlobalFiniteBounds(this->Controller, inputPoints);
  const fd3::PeriodicBox box = fd3vtk::PeriodicBoxOf(
    fd3vtk::BoxInUse(this, this->UseInputBounds, this->Bounds, bounds), this->Periodic);
  const std::string problem = fd3vtk::PeriodicBoxProblem(box); // alike on every rank
  if (!problem.empty())
  {
    if (root)
    {
      vtkWarningMacro(
        "Cannot triangulate: " << problem << "; the output holds the points and no cells");
    }
    fd3vtk::SetPointsWithoutCells(output, inputPoints, inputData);
    return 1;
  }

  fd3vtk::DistributedRun run(this->Controller, fd3vtk::ThreadCount(this->NumberOfThreads));
  fd3vtk::PeriodicRun periodic(run, box);
  if (!periodic.Redistribute(input, inputPoints))
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed, output, inputPoints, inputData);
  }
  if (run.InputPoints == 0)
  {
    if (root)
    {
      vtkWarningMacro("Cannot triangulate; no input points");
    }
    fd3vtk::SetPointsWithoutCells(output, nullptr, nullptr);
    return 1;
  }
  const fd3::Options options = this->KernelOptions(bounds.diagonal());
  fd3::PeriodicPieceTriangulation piece;
  std::vector<double> ghostDensity;
  if (!periodic.Run([&](fd3::PeriodicPiece own, double& widerHalo) {
        // An alpha shape's triangles and edges are kept by the tetrahedra all round them: the
        // rank walks its points' stars.
        own.stars = this->Alpha > 0;
        piece = fd3::triangulatePeriodicPiece(
          periodic.Xyz.data(), periodic.Xyz.size() / 3, box, own, this->ComputeDensity, options);
        widerHalo = piece.widerHalo;
        return piece.triangulation.status != fd3::Status::Aborted;
      }))
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed, output, inputPoints, inputData);
  }
  this->NumberOfGhostPoints = periodic.GhostPoints;

  // The pieces widen their halo until every rank with points has tetrahedra, or none has.
  const fd3::Status status = fd3vtk::StatusOfAllRanks(this->Controller, piece.triangulation.status);
  // A rank's densities are there where its piece is Ok, and sent where all are: every rank then
  // has tetrahedra or no points.
  if (status == fd3::Status::Ok && this->ComputeDensity &&
    !periodic.GhostValues(piece.density, ghostDensity))
  {
    return this->Stop(run.Ranks.Failure, run.Ranks.AnyFailed, output, inputPoints, inputData);
  }
  fd3::Statistics figures = piece.triangulation.stats;
  fd3vtk::SumFigures(this->Controller, figures);
  figures.inputPoints = static_cast<std::size_t>(run.InputPoints);
  this->RecordFigures(figures);
  const bool hasCells =
    root ? this->ReportOnInput(status, figures, run.InputPoints) : status == fd3::Status::Ok;
  if (!hasCells)
  {
    fd3vtk::SetPointsWithoutCells(output, inputPoints, inputData);
    return 1;
  }
  try // no rank waits for this one from here on
  {
    const auto outputStart = std::chrono::steady_clock::now();
    const std::size_t own = run.OwnCount();
    fd3::PeriodicPlacement placement =
      fd3::placePeriodic(periodic.Xyz.data(), own, piece.triangulation, box);
    vtkNew<vtkPoints> points;
    points->SetDataType(run.OutputPointType());
    points->SetNumberOfPoints(static_cast<vtkIdType>(own));
    for (std::size_t i = 0; i < own; ++i)
    {
      points->SetPoint(static_cast<vtkIdType>(i), &periodic.Xyz[3 * i]);
    }
    // A rank whose points are all NaN or Inf has no piece, and no densities.
    std::vector<double> density = std::move(piece.density);
    density.resize(own, std::numeric_limits<double>::quiet_NaN());
    density.insert(density.end(), ghostDensity.begin(), ghostDensity.end());
    this->SetPeriodicOutput(output, points, periodic.PointData(), periodic.Xyz.data(), placement,
      std::move(density), periodic.Ids.data(), this->Alpha > 0 ? &piece.owned : nullptr);
    // SourcePointId holds the input ids: GlobalIds, which images repeat, would pass for unique.
    output->GetPointData()->RemoveArray(fd3vtk::kInputIds);
    figures.secondsOutput +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - outputStart).count();
  }
  catch (const std::exception& error)
  {
    return this->Stop(error.what(), true, output, inputPoints, inputData);
  }
  this->RecordFigures(figures);
  this->AddFigures(output->GetFieldData());
  return 1;
}

int vtkPFastDelaunay3D::Stop(const std::string& failure, bool anyFailed,
  vtkUnstructuredGrid* output, vtkPoints* inputPoints, vtkPointData* inputData)
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
    vtkErrorMacro(
      "Triangulation failed: " << failure << "; the output holds the points and no cells");
  }
  else if (this->Controller->GetLocalProcessId() == 0)
  {
    vtkErrorMacro("Triangulation failed on another rank; the output holds the points and no cells");
  }
  fd3vtk::SetPointsWithoutCells(output, inputPoints, inputData);
  return 0;
}

void vtkPFastDelaunay3D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "NumberOfGhostPoints: " << this->NumberOfGhostPoints << "\n";
}
