/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkFastVoronoi3D.h"

#include "FilterArrays.h"
#include "FilterBox.h"
#include "FilterCells.h"
#include "FilterInput.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Periodic.h"
#include "fd3/Voronoi.h"
#include "fd3/Workers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkFastVoronoi3D);

namespace
{
using fd3vtk::AddFieldValue;
using fd3vtk::NamedArray;
} // namespace

vtkFastVoronoi3D::vtkFastVoronoi3D()
{
  this->SetNumberOfOutputPorts(2);
}

int vtkFastVoronoi3D::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkUnstructuredGrid" : "vtkPolyData");
  return 1;
}

vtkPolyData* vtkFastVoronoi3D::GetFacesOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkFastVoronoi3D::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkFastVoronoi3D::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  vtkPolyData* faces = vtkPolyData::GetData(outputVector, 1);
  this->RecordFigures(0, 0, 0);
  output->Initialize();
  faces->Initialize();
  const vtkIdType numberOfPoints = input ? input->GetNumberOfPoints() : 0;
  if (numberOfPoints == 0)
  {
    if (outputVector->GetInformationObject(0)->Get(
          vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) <= 1)
    {
      vtkWarningMacro("No Voronoi cells: no input points");
    }
    return 1;
  }

  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) > 1)
  {
    vtkWarningMacro("Running on several processes: each computes the cells of its own points "
                    "alone, so cells next to another process's points are too large");
  }

  return this->OutputCells(input,
    fd3vtk::WeightsChosen(this) ? this->GetInputArrayToProcess(0, inputVector) : nullptr, output,
    faces);
}

int vtkFastVoronoi3D::OutputCells(
  vtkDataSet* input, vtkDataArray* weightArray, vtkUnstructuredGrid* output, vtkPolyData* faces)
{
  // VTK points in -> Core -> VTK polyhedra out.
  const vtkIdType numberOfPoints = input->GetNumberOfPoints();
  vtkSmartPointer<vtkPoints> points =
    fd3vtk::PointsInPrecision(input, vtkAlgorithm::DEFAULT_PRECISION);
  std::vector<double> converted;
  const double* xyz = fd3vtk::CoordinatesAsDoubles(points, converted);
  std::vector<double> weights;
  if (weightArray)
  {
    std::string problem;
    weights = fd3vtk::PointWeights(weightArray, numberOfPoints, this->WeightsAreRadii,
      static_cast<std::size_t>(numberOfPoints), problem);
    if (weights.empty())
    {
      vtkErrorMacro("No Voronoi cells: " << problem);
      return 0;
    }
  }
  fd3::VoronoiCells cells;
  try
  {
    const auto kernelStart = std::chrono::steady_clock::now();
    cells = this->ComputeCells(
      xyz, weights.empty() ? nullptr : weights.data(), static_cast<std::size_t>(numberOfPoints));
    this->KernelSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - kernelStart).count();
  }
  catch (
    const std::exception& failure) // out of memory, more points than 32-bit ids hold, no period
  {
    vtkErrorMacro("Voronoi cells failed: " << failure.what() << "; the output is empty");
    return 0;
  }
  if (cells.status == fd3::Status::Aborted)
  {
    return 1;
  }
  this->RecordFigures(static_cast<vtkIdType>(cells.numberOfCells()),
    static_cast<vtkIdType>(cells.stats.duplicatesMerged),
    static_cast<vtkIdType>(cells.stats.nonFinitePoints),
    static_cast<vtkIdType>(cells.stats.hiddenPoints));
  if (!this->ReportOnInput(cells.status, cells.box, numberOfPoints, !weights.empty()))
  {
    return 1;
  }
  const auto conversionStart = std::chrono::steady_clock::now();
  fd3::Workers workers(fd3vtk::ThreadCount(this->NumberOfThreads));
  vtkSmartPointer<vtkPoints> vertices = this->SetGeometry(output, cells, xyz, workers);
  this->UpdateProgress(0.9);
  AddCellData(output, cells, input->GetPointData(), workers);
  if (this->GenerateFaces)
  {
    SetFaces(faces, cells, vertices, [](std::uint32_t id) { return vtkIdType(id); });
  }
  this->ConversionSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - conversionStart).count();
  this->AddFigures(output->GetFieldData());
  return 1;
}

fd3::VoronoiCells vtkFastVoronoi3D::ComputeCells(
  const double* xyz, const double* weights, std::size_t count)
{
  if (!fd3vtk::AnyPeriodic(this->Periodic))
  {
    return fd3::voronoiCells(xyz, weights, count, this->KernelOptions());
  }
  const fd3::Bounds inputBounds =
    fd3::finiteBounds(xyz, count, fd3vtk::ThreadCount(this->NumberOfThreads));
  const fd3::VoronoiOptions options = this->KernelOptions(inputBounds);
  const fd3::PeriodicBox box = fd3vtk::PeriodicBoxOf(options.box, this->Periodic);
  const std::string problem = fd3vtk::PeriodicBoxProblem(box);
  if (!problem.empty())
  {
    throw std::invalid_argument(problem);
  }
  return fd3::voronoiCellsPeriodic(xyz, weights, count, box, options);
}

fd3::VoronoiOptions vtkFastVoronoi3D::KernelOptions()
{
  return this->KernelOptions(fd3::Bounds()); // empty: the kernel bounds the points
}

fd3::VoronoiOptions vtkFastVoronoi3D::KernelOptions(const fd3::Bounds& inputBounds)
{
  fd3::VoronoiOptions options;
  options.box = fd3vtk::BoxInUse(this, this->UseInputBounds, this->Bounds, inputBounds);
  options.threads = fd3vtk::ThreadCount(this->NumberOfThreads);
  options.density = this->ComputeDensity;
  options.polyhedra = this->GeneratePolyhedra || this->GenerateFaces;
  options.progress = [this](double fraction) {
    this->UpdateProgress(0.8 * fraction);
    return !fd3vtk::AbortRequested(this);
  };
  return options;
}

void vtkFastVoronoi3D::RecordFigures(
  vtkIdType generators, vtkIdType duplicates, vtkIdType invalid, vtkIdType hidden)
{
  this->NumberOfGenerators = generators;
  this->NumberOfDuplicatePoints = duplicates;
  this->NumberOfInvalidPoints = invalid;
  this->NumberOfHiddenPoints = hidden;
}

bool vtkFastVoronoi3D::ReportOnInput(
  fd3::Status status, const fd3::Bounds& box, vtkIdType numberOfPoints, bool weighted)
{
  if (status != fd3::Status::Ok)
  {
    vtkWarningMacro("No Voronoi cells: " << fd3::toString(status));
    return false;
  }
  if (this->NumberOfDuplicatePoints > 0 || this->NumberOfInvalidPoints > 0)
  {
    vtkWarningMacro(<< this->NumberOfDuplicatePoints + this->NumberOfInvalidPoints << " of "
                    << numberOfPoints
                    << " points have no cell of their own: " << this->NumberOfDuplicatePoints
                    << " exact duplicates (the first copy's cell is theirs), "
                    << this->NumberOfInvalidPoints << " with NaN or infinite coordinates"
                    << (weighted ? " or weight" : ""));
  }
  if (!(box.volume() > 0))
  {
    vtkWarningMacro("The clipping box has no volume: every cell is empty (set Bounds)");
  }
  return true;
}

vtkSmartPointer<vtkPoints> vtkFastVoronoi3D::SetGeometry(vtkUnstructuredGrid* output,
  fd3::VoronoiCells& cells, const double* xyz, fd3::Workers& workers) const
{
  vtkSmartPointer<vtkPoints> vertices;
  if (this->GeneratePolyhedra || this->GenerateFaces)
  {
    vertices = fd3vtk::PointsOf(std::move(cells.points));
  }
  if (this->GeneratePolyhedra)
  {
    output->SetPoints(vertices);
    fd3vtk::SetPolyhedra(output, cells, workers);
  }
  else
  {
    SetGenerators(output, cells, xyz, workers);
  }
  return vertices;
}

void vtkFastVoronoi3D::SetGenerators(vtkUnstructuredGrid* output, const fd3::VoronoiCells& cells,
  const double* xyz, fd3::Workers& workers)
{
  const std::size_t n = cells.numberOfCells();
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(static_cast<vtkIdType>(n));
  double* out = coordinates->GetPointer(0);
  workers.forRanges(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
    {
      std::copy_n(xyz + 3 * std::size_t(cells.generators[c]), 3, out + 3 * c);
    }
  });
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  output->SetPoints(points);
  fd3vtk::SetVertexCells(output, static_cast<vtkIdType>(n));
}

void vtkFastVoronoi3D::AddCellData(vtkUnstructuredGrid* output, const fd3::VoronoiCells& cells,
  vtkPointData* pointData, fd3::Workers& workers)
{
  const auto n = static_cast<vtkIdType>(cells.numberOfCells());
  vtkCellData* cellData = output->GetCellData();
  if (pointData && pointData->GetNumberOfArrays() > 0)
  {
    vtkNew<vtkIdList> from, to;
    from->SetNumberOfIds(n);
    to->SetNumberOfIds(n);
    for (vtkIdType c = 0; c < n; ++c)
    {
      from->SetId(c, cells.generators[c]);
      to->SetId(c, c);
    }
    cellData->CopyAllocate(pointData, n);
    cellData->CopyData(pointData, from, to);
  }
  auto generatorId = NamedArray<vtkIdTypeArray>("GeneratorId", n);
  auto volume = NamedArray<vtkDoubleArray>("Volume", n);
  auto area = NamedArray<vtkDoubleArray>("SurfaceArea", n);
  auto faces = NamedArray<vtkIntArray>("NumberOfFaces", n);
  auto neighbors = NamedArray<vtkIntArray>("NumberOfNeighbors", n);
  workers.forRanges(cells.numberOfCells(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t cell = begin; cell < end; ++cell)
    {
      const auto c = static_cast<vtkIdType>(cell);
      generatorId->SetValue(c, cells.generators[cell]);
      volume->SetValue(c, cells.volumes[cell]);
      area->SetValue(c, cells.areas[cell]);
      faces->SetValue(c, static_cast<int>(cells.numberOfFaces(cell)));
      neighbors->SetValue(c, static_cast<int>(cells.numberOfNeighbors(cell)));
    }
  });
  std::vector<vtkDataArray*> arrays = { generatorId, volume, area, faces, neighbors };
  vtkSmartPointer<vtkDoubleArray> density;
  if (!cells.densities.empty())
  {
    density = NamedArray<vtkDoubleArray>("Density", n);
    std::copy(cells.densities.begin(), cells.densities.end(), density->GetPointer(0));
    arrays.push_back(density);
  }
  // The cells' own arrays take the place of input arrays of the same name.
  for (vtkDataArray* array : arrays)
  {
    cellData->RemoveArray(array->GetName());
    cellData->AddArray(array);
  }
  cellData->SetActiveScalars("Volume");
}

void vtkFastVoronoi3D::SetFaces(vtkPolyData* faces, const fd3::VoronoiCells& cells,
  vtkPoints* points, const std::function<vtkIdType(std::uint32_t)>& inputId)
{
  // Which faces, and where each one's ids go: one pass to count, one to write.
  const std::size_t n = cells.numberOfCells();
  std::vector<vtkIdType> generator(n), kept;
  for (std::size_t c = 0; c < n; ++c)
  {
    generator[c] = inputId(cells.generators[c]);
    for (std::size_t f = cells.cellFaces[c]; f < cells.cellFaces[c + 1]; ++f)
    {
      const std::uint32_t q = cells.faceNeighbors[f];
      if (q >= fd3::kBoxFace || generator[c] < inputId(q))
      {
        kept.push_back(static_cast<vtkIdType>(f));
        kept.push_back(static_cast<vtkIdType>(c));
      }
    }
  }
  const auto count = static_cast<vtkIdType>(kept.size() / 2);
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(count + 1);
  offsets->SetValue(0, 0);
  for (vtkIdType k = 0; k < count; ++k)
  {
    const auto f = static_cast<std::size_t>(kept[2 * k]);
    offsets->SetValue(
      k + 1, offsets->GetValue(k) + vtkIdType(cells.faceStart[f + 1] - cells.faceStart[f]));
  }
  connectivity->SetNumberOfValues(offsets->GetValue(count));
  auto ids = NamedArray<vtkIdTypeArray>("GeneratorIds", 0);
  ids->SetNumberOfComponents(2);
  ids->SetNumberOfTuples(count);
  auto area = NamedArray<vtkDoubleArray>("Area", count);
  const double* xyz = vtkDoubleArray::SafeDownCast(points->GetData())->GetPointer(0);
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType k = begin; k < end; ++k)
    {
      const auto f = static_cast<std::size_t>(kept[2 * k]);
      const std::size_t first = cells.faceStart[f], last = cells.faceStart[f + 1];
      double normal[3] = { 0, 0, 0 };
      for (std::size_t i = first; i < last; ++i)
      {
        connectivity->SetValue(offsets->GetValue(k) + vtkIdType(i - first), cells.faceVertices[i]);
        const double* a = xyz + 3 * std::size_t(cells.faceVertices[i]);
        const double* b = xyz + 3 * std::size_t(cells.faceVertices[i + 1 < last ? i + 1 : first]);
        normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
        normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
        normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
      }
      const std::uint32_t q = cells.faceNeighbors[f];
      ids->SetTypedComponent(k, 0, generator[static_cast<std::size_t>(kept[2 * k + 1])]);
      ids->SetTypedComponent(k, 1, q >= fd3::kBoxFace ? -1 : inputId(q));
      area->SetValue(k, std::sqrt(vtkMath::Dot(normal, normal)) / 2);
    }
  });
  vtkNew<vtkCellArray> polygons;
  polygons->SetData(offsets, connectivity);
  faces->SetPoints(points);
  faces->SetPolys(polygons);
  faces->GetCellData()->AddArray(ids);
  faces->GetCellData()->AddArray(area);
  faces->GetCellData()->SetActiveScalars("Area");
}

void vtkFastVoronoi3D::AddFigures(vtkFieldData* fields) const
{
  if (this->NumberOfDuplicatePoints > 0 || this->NumberOfInvalidPoints > 0)
  {
    AddFieldValue(fields, "NumberOfDuplicatePoints", double(this->NumberOfDuplicatePoints));
    AddFieldValue(fields, "NumberOfInvalidPoints", double(this->NumberOfInvalidPoints));
  }
  if (this->NumberOfHiddenPoints > 0)
  {
    AddFieldValue(fields, "NumberOfHiddenPoints", double(this->NumberOfHiddenPoints));
  }
}

void vtkFastVoronoi3D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "UseInputBounds: " << this->UseInputBounds << "\n";
  os << indent << "Periodic: " << this->Periodic[0] << " " << this->Periodic[1] << " "
     << this->Periodic[2] << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Number Of Threads: " << this->NumberOfThreads << "\n";
  os << indent << "WeightsAreRadii: " << this->WeightsAreRadii << "\n";
  os << indent << "Compute Density: " << this->ComputeDensity << "\n";
  os << indent << "Generate Polyhedra: " << this->GeneratePolyhedra << "\n";
  os << indent << "Generate Faces: " << this->GenerateFaces << "\n";
  os << indent << "Number Of Generators: " << this->NumberOfGenerators << "\n";
  os << indent << "Number Of Duplicate Points: " << this->NumberOfDuplicatePoints << "\n";
  os << indent << "Number Of Invalid Points: " << this->NumberOfInvalidPoints << "\n";
  os << indent << "Kernel Seconds: " << this->KernelSeconds << "\n";
  os << indent << "Conversion Seconds: " << this->ConversionSeconds << "\n";
}
