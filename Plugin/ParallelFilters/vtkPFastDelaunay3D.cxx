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

#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include <chrono>
#include <exception>
#include <string>
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
    // Not distributed yet: the first rank triangulates every rank's points, as one process.
    vtkSmartPointer<vtkPointSet> all =
      fd3vtk::GatheredPoints(this->Controller, input, this, "Cannot triangulate; no input points");
    if (!all)
    {
      return 1;
    }
    const bool weighted =
      fd3vtk::WeightsChosen(this) && this->GetInputArrayToProcess(0, all) != nullptr;
    return this->TriangulatePeriodic(all, output, weighted);
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
