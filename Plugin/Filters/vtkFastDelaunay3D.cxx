/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkFastDelaunay3D.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Delaunay.h"

#include <exception>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkFastDelaunay3D);

namespace
{
/// The input's points: those of a vtkPointSet as they are (shared with the output), or built from
/// any other dataset (image data, rectilinear grids), whose points are implicit.
vtkSmartPointer<vtkPoints> InputPoints(vtkDataSet* input)
{
  if (auto* pointSet = vtkPointSet::SafeDownCast(input))
  {
    return pointSet->GetPoints();
  }
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(input->GetNumberOfPoints());
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    points->SetPoint(i, input->GetPoint(i));
  }
  return points;
}

/// The point coordinates as x,y,z doubles: the array itself when it already is one, else a copy.
const double* PointsAsDoubles(vtkPoints* points, std::vector<double>& copy)
{
  vtkDataArray* data = points->GetData();
  if (auto* doubles = vtkDoubleArray::FastDownCast(data))
  {
    return doubles->GetPointer(0);
  }
  const vtkIdType n = points->GetNumberOfPoints();
  copy.resize(3 * static_cast<std::size_t>(n));
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      data->GetTuple(i, copy.data() + 3 * i);
    }
  });
  return copy.data();
}

/// VTK_TETRA cells from the kernel's tetrahedra, filling offsets and connectivity directly. The
/// cell array uses 32-bit storage whenever the ids fit, which halves its memory.
template <typename IdArray>
vtkSmartPointer<vtkCellArray> MakeTetraCells(const std::vector<std::uint32_t>& tets)
{
  using Id = typename IdArray::ValueType;
  const vtkIdType numberOfTets = static_cast<vtkIdType>(tets.size() / 4);
  vtkNew<IdArray> offsets;
  vtkNew<IdArray> connectivity;
  offsets->SetNumberOfValues(numberOfTets + 1);
  connectivity->SetNumberOfValues(4 * numberOfTets);
  Id* offset = offsets->GetPointer(0);
  Id* ids = connectivity->GetPointer(0);
  vtkSMPTools::For(0, numberOfTets, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType t = begin; t < end; ++t)
    {
      offset[t] = static_cast<Id>(4 * t);
      for (int i = 0; i < 4; ++i)
      {
        ids[4 * t + i] = static_cast<Id>(tets[4 * t + i]);
      }
    }
  });
  offset[numberOfTets] = static_cast<Id>(4 * numberOfTets);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

vtkSmartPointer<vtkCellArray> MakeTetraCells(const std::vector<std::uint32_t>& tets)
{
  const bool fits32 = tets.size() < static_cast<std::size_t>(std::numeric_limits<vtkTypeInt32>::max());
  return fits32 ? MakeTetraCells<vtkTypeInt32Array>(tets) : MakeTetraCells<vtkTypeInt64Array>(tets);
}
} // namespace

vtkFastDelaunay3D::vtkFastDelaunay3D() = default;

int vtkFastDelaunay3D::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkFastDelaunay3D::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  const vtkIdType numberOfPoints = input ? input->GetNumberOfPoints() : 0;
  if (numberOfPoints == 0)
  {
    vtkWarningMacro("Cannot triangulate; no input points");
    return 1;
  }

  // VTK arrays in -> Core -> VTK arrays out.
  vtkSmartPointer<vtkPoints> points = InputPoints(input);
  std::vector<double> converted;
  const double* xyz = PointsAsDoubles(points, converted);
  fd3::Options options;
  options.pointsPerCell = this->GridResolution;
  options.volumeThreshold = this->VolumeThreshold;
  options.order = static_cast<fd3::InsertionOrder>(this->InsertionOrder);
  options.randomSeed = static_cast<std::uint64_t>(this->RandomSeed);
  options.computeNeighbors = false;
  options.progress = [this](double fraction) {
    this->UpdateProgress(fraction);
    return !this->CheckAbort();
  };
  fd3::Triangulation result;
  try
  {
    result = fd3::triangulate(xyz, static_cast<std::size_t>(numberOfPoints), options);
  }
  catch (const std::exception& failure) // out of memory, or more points than 32-bit ids hold
  {
    vtkErrorMacro("Triangulation failed: " << failure.what() << "; the output is empty");
    output->Initialize();
    return 0;
  }
  if (result.status == fd3::Status::Aborted)
  {
    output->Initialize();
    return 1;
  }

  const fd3::Statistics& stats = result.stats;
  this->NumberOfInsertedPoints = static_cast<vtkIdType>(stats.insertedPoints);
  this->NumberOfDuplicatePoints = static_cast<vtkIdType>(stats.duplicatesMerged);
  this->NumberOfInvalidPoints = static_cast<vtkIdType>(stats.nonFinitePoints);
  this->NumberOfTetrahedra = static_cast<vtkIdType>(stats.tetrahedra);
  this->MeanWalkLength = stats.meanWalk();
  this->KernelSeconds = stats.secondsTotal;
  if (stats.nonFinitePoints > 0)
  {
    vtkErrorMacro(<< stats.nonFinitePoints << " of " << numberOfPoints
                  << " points have NaN or infinite coordinates; they are left out of the "
                     "tetrahedralization and remain in the output as unused points");
  }
  if (result.status != fd3::Status::Ok)
  {
    vtkWarningMacro("Cannot triangulate: " << fd3::toString(result.status)
                                           << "; the output holds the points and no cells");
  }
  if (stats.underflowRisks > 0)
  {
    vtkWarningMacro("Some points are closer together than 2^-190 of the extent of the point set: "
                    "exactness is not guaranteed for "
                    << stats.underflowRisks << " decisions");
  }
  if (stats.duplicatesMerged > 0)
  {
    vtkWarningMacro(<< stats.duplicatesMerged
                    << " exact duplicate points were merged; they remain in the output as unused "
                       "points");
  }

  output->SetPoints(points);
  output->GetPointData()->PassData(input->GetPointData());
  output->SetCells(VTK_TETRA, MakeTetraCells(result.tetrahedra));
  return 1;
}

void vtkFastDelaunay3D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GridResolution: " << this->GridResolution << "\n";
  os << indent << "VolumeThreshold: " << this->VolumeThreshold << "\n";
  os << indent << "InsertionOrder: " << this->InsertionOrder << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "NumberOfInsertedPoints: " << this->NumberOfInsertedPoints << "\n";
  os << indent << "NumberOfDuplicatePoints: " << this->NumberOfDuplicatePoints << "\n";
  os << indent << "NumberOfInvalidPoints: " << this->NumberOfInvalidPoints << "\n";
  os << indent << "NumberOfTetrahedra: " << this->NumberOfTetrahedra << "\n";
  os << indent << "MeanWalkLength: " << this->MeanWalkLength << "\n";
  os << indent << "KernelSeconds: " << this->KernelSeconds << "\n";
}
