/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkFastDelaunay3D.h"

#include "FilterArrays.h"
#include "FilterBox.h"
#include "FilterCells.h"
#include "FilterInput.h"
#include "PointInsertion.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkIncrementalPointLocator.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointLocator.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Bounds.h"
#include "fd3/Delaunay.h"
#include "fd3/Measures.h"
#include "fd3/Periodic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkFastDelaunay3D);

namespace
{

/// vtkDelaunay3D's bounding octahedron (centre +- offset * diagonal along each axis, of the
/// finite points' box) as the 6 points after the first `count` of `points`.
void SetOctahedron(vtkPoints* points, vtkIdType count, const fd3::Bounds& bounds, double offset)
{
  double centre[3], farthest = 0;
  for (int a = 0; a < 3; ++a)
  {
    centre[a] = bounds.lo[a] / 2 + bounds.hi[a] / 2;
    farthest = std::max(farthest, std::fabs(centre[a]));
  }
  // No further than VTK_DOUBLE_MAX - |centre| (halved against the rounding of the sum).
  const double diagonal = bounds.diagonal();
  const double length =
    std::min(offset * (diagonal > 0 ? diagonal : 1.0), (VTK_DOUBLE_MAX - farthest) / 2);
  for (int k = 0; k < 6; ++k)
  {
    double x[3] = { centre[0], centre[1], centre[2] };
    x[k / 2] += (k % 2 ? length : -length);
    points->SetPoint(count + k, x);
  }
}

/// "Circumradius", "Volume" and "RadiusEdgeRatio" cell arrays, as requested.
void AddCellMeasures(
  vtkUnstructuredGrid* output, const double* xyz, bool circumradius, bool volume, bool ratio)
{
  const vtkIdType n = output->GetNumberOfCells();
  std::vector<vtkSmartPointer<vtkDoubleArray>> arrays(3);
  const char* names[3] = { "Circumradius", "Volume", "RadiusEdgeRatio" };
  const bool wanted[3] = { circumradius, volume, ratio };
  for (int a = 0; a < 3; ++a)
  {
    if (wanted[a])
    {
      arrays[a] = vtkSmartPointer<vtkDoubleArray>::New();
      arrays[a]->SetName(names[a]);
      arrays[a]->SetNumberOfValues(n);
      output->GetCellData()->AddArray(arrays[a]);
    }
  }
  vtkSMPThreadLocalObject<vtkIdList> scratch; // the cell array stores 32-bit ids: a copy is needed
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    vtkIdList* idList = scratch.Local();
    for (vtkIdType c = begin; c < end; ++c)
    {
      output->GetCells()->GetCellAtId(c, idList);
      const vtkIdType size = idList->GetNumberOfIds();
      const vtkIdType* ids = idList->GetPointer(0);
      const double* p[4];
      for (vtkIdType k = 0; k < size && k < 4; ++k)
      {
        p[k] = xyz + 3 * ids[k];
      }
      double values[3] = { 0, 0, 0 };
      if (size == 4)
      {
        values[0] = std::sqrt(fd3::tetrahedronCircumradius2(p[0], p[1], p[2], p[3]));
        values[1] = fd3::sixVolume(p[0], p[1], p[2], p[3]) / 6;
        values[2] = fd3::radiusEdgeRatio(p[0], p[1], p[2], p[3]);
      }
      else if (size == 3)
      {
        values[0] = std::sqrt(fd3::triangleCircumradius2(p[0], p[1], p[2]));
      }
      else if (size == 2)
      {
        values[0] = std::sqrt(fd3::distance2(p[0], p[1])) / 2;
      }
      for (int a = 0; a < 3; ++a)
      {
        if (arrays[a])
        {
          arrays[a]->SetValue(c, values[a]);
        }
      }
    }
  });
}

/// What the tetrahedralization leaves out, by cause, with what keeps it; empty when nothing is.
std::string LeftOutPoints(const fd3::Statistics& stats, bool weighted)
{
  std::ostringstream causes;
  const char* separator = "";
  if (stats.duplicatesMerged > 0)
  {
    causes << separator << stats.duplicatesMerged
           << " exact duplicates (merged: points at one position make one vertex)";
    separator = "; ";
  }
  if (stats.closePointsSkipped > 0)
  {
    causes << separator << stats.closePointsSkipped
           << " within Tolerance of an inserted point (Tolerance 0 keeps them)";
    separator = "; ";
  }
  if (stats.nonFinitePoints > 0)
  {
    causes << separator << stats.nonFinitePoints
           << (weighted ? " with NaN or infinite coordinates or weight (no position or power to "
                          "triangulate)"
                        : " with NaN or infinite coordinates (no position to triangulate)");
  }
  return causes.str();
}

/// The output's points: the input's `points`, then the placement's images, in their precision.
void SetPointsAndImages(
  vtkUnstructuredGrid* output, vtkPoints* points, const fd3::PeriodicPlacement& placement)
{
  const vtkIdType count = points->GetNumberOfPoints();
  const vtkIdType images = static_cast<vtkIdType>(placement.numberOfImages());
  vtkNew<vtkPoints> all;
  all->SetDataType(points->GetDataType());
  all->SetNumberOfPoints(count + images);
  all->GetData()->InsertTuples(0, count, 0, points->GetData());
  for (vtkIdType k = 0; k < images; ++k)
  {
    all->SetPoint(count + k, &placement.imagePoints[3 * static_cast<std::size_t>(k)]);
  }
  output->SetPoints(all);
}

/// The input's point data on its points, each image with its input point's values, and
/// "SourcePointId": the input point each output point copies (ids[i] of point i, where given).
void SetPointDataAndImages(vtkPointData* out, vtkPointData* in, vtkIdType count,
  const fd3::PeriodicPlacement& placement, const std::uint32_t* ids)
{
  const vtkIdType images = static_cast<vtkIdType>(placement.numberOfImages());
  vtkNew<vtkIdList> sources, targets;
  sources->SetNumberOfIds(images);
  targets->SetNumberOfIds(images);
  auto sourceId = fd3vtk::NamedArray<vtkIdTypeArray>("SourcePointId", count + images);
  for (vtkIdType i = 0; i < count; ++i)
  {
    sourceId->SetValue(i, ids ? ids[i] : i);
  }
  for (vtkIdType k = 0; k < images; ++k)
  {
    sources->SetId(k, placement.imageSources[k]);
    targets->SetId(k, count + k);
    const std::uint32_t source = placement.imageSources[k];
    sourceId->SetValue(count + k, ids ? ids[source] : source);
  }
  if (in)
  {
    out->CopyAllocate(in, count + images);
    out->CopyData(in, 0, count, 0);
    out->CopyData(in, sources, targets);
  }
  out->AddArray(sourceId);
}

/// Of the alpha shape of an MPI rank's placed stars (`count` own points, input ids `ids`), what
/// the rank owns: the tetrahedra `owned` says, the triangles and lines whose least vertex (least
/// input id) is one of its points, and its points' vertex cells.
void KeepOwned(fd3::AlphaComplex& shape, const fd3::PeriodicPlacement& placement, std::size_t count,
  const std::uint32_t* ids, const std::vector<std::uint8_t>& owned)
{
  auto source = [&](std::uint32_t v) { return v < count ? v : placement.imageSources[v - count]; };
  auto keep = [&](std::vector<std::uint32_t>& list, int size) {
    std::size_t kept = 0;
    for (std::size_t s = 0; s < list.size(); s += size)
    {
      std::uint32_t least = source(list[s]);
      for (int k = 1; k < size; ++k)
      {
        least = ids[source(list[s + k])] < ids[least] ? source(list[s + k]) : least;
      }
      if (least < count)
      {
        kept += std::copy_n(&list[s], size, &list[kept]) - &list[kept];
      }
    }
    list.resize(kept);
  };
  keep(shape.triangles, 3);
  keep(shape.lines, 2);
  shape.tetrahedra.erase(std::remove_if(shape.tetrahedra.begin(), shape.tetrahedra.end(),
                           [&](std::uint32_t t) { return !owned[t]; }),
    shape.tetrahedra.end());
}

using fd3vtk::AddFieldValue;
using fd3vtk::CellBlock;
using fd3vtk::CoordinatesAsDoubles;
using fd3vtk::KeepCells;
using fd3vtk::PointsInPrecision;
using fd3vtk::SetCells;
using fd3vtk::SetPointsWithoutCells;
using fd3vtk::SetTetrahedra;
using fd3vtk::ThreadCount;

/// The kernel's run as both paths make it: `run` returns its result. A failure (out of memory,
/// more points than 32-bit ids hold) is an error that leaves the points and no cells; an abort
/// leaves an empty output. Returns whether to go on; where not, `done` is RequestData's value.
template <typename Result, typename Run>
bool KernelRan(vtkAlgorithm* self, const Run& run, Result& result, vtkUnstructuredGrid* output,
  vtkPoints* points, vtkPointData* pointData, int& done)
{
  try
  {
    result = run();
  }
  catch (const std::exception& failure)
  {
    vtkErrorWithObjectMacro(self,
      "Triangulation failed: " << failure.what() << "; the output holds the points and no cells");
    SetPointsWithoutCells(output, points, pointData);
    done = 0;
    return false;
  }
  if (result.status == fd3::Status::Aborted)
  {
    output->Initialize();
    done = 1;
    return false;
  }
  return true;
}
} // namespace

vtkFastDelaunay3D::vtkFastDelaunay3D() = default;
vtkFastDelaunay3D::~vtkFastDelaunay3D() = default;

void vtkFastDelaunay3D::SetLocator(vtkIncrementalPointLocator* locator)
{
  if (this->Locator != locator)
  {
    this->Locator = locator;
    this->Modified();
  }
}

void vtkFastDelaunay3D::CreateDefaultLocator()
{
  if (!this->Locator)
  {
    auto locator = vtkSmartPointer<vtkPointLocator>::New();
    locator->SetDivisions(25, 25, 25);
    this->Locator = locator;
  }
}

vtkMTimeType vtkFastDelaunay3D::GetMTime()
{
  const vtkMTimeType mtime = this->Superclass::GetMTime();
  return this->Locator ? std::max(mtime, this->Locator->GetMTime()) : mtime;
}

vtkUnstructuredGrid* vtkFastDelaunay3D::InitPointInsertion(
  double center[3], double length, vtkIdType numPts, vtkPoints*& points)
{
  vtkUnstructuredGrid* mesh = vtkUnstructuredGrid::New();
  mesh->EditableOn(); // its links change with every point
  this->Insertion.reset();
  this->RecordFigures(fd3::Statistics());
  if (numPts <= 0 || !points)
  {
    return mesh;
  }
  length = length > 0 ? length : 1.0; // NaN too
  try
  {
    this->Insertion =
      std::make_unique<fd3vtk::PointInsertion>(mesh, points, center, length, numPts, this->Locator);
  }
  catch (const std::exception& failure) // a center or length beyond the doubles, out of memory
  {
    vtkErrorMacro("InitPointInsertion failed: " << failure.what());
    return mesh;
  }
  points->Delete(); // the mesh holds it: vtkDelaunay3D's contract takes the caller's reference
  return mesh;
}

void vtkFastDelaunay3D::InsertPoint(
  vtkUnstructuredGrid* Mesh, vtkPoints* points, vtkIdType id, double x[3], vtkIdList* holeTetras)
{
  if (!this->Insertion || !Mesh || !points)
  {
    vtkErrorMacro("InsertPoint: no insertion under way (InitPointInsertion starts one)");
    return;
  }
  vtkNew<vtkIdList> unused;
  try
  {
    switch (this->Insertion->Insert(Mesh, points, id, x, holeTetras ? holeTetras : unused.Get()))
    {
      case fd3vtk::PointInsertion::Outcome::Inserted:
        ++this->NumberOfInsertedPoints;
        break;
      case fd3vtk::PointInsertion::Outcome::Merged:
        ++this->NumberOfDuplicatePoints;
        break;
      case fd3vtk::PointInsertion::Outcome::NotFinite:
        ++this->NumberOfInvalidPoints;
        break;
    }
  }
  catch (const std::exception& failure) // out of memory
  {
    vtkErrorMacro("InsertPoint failed: " << failure.what());
  }
}

void vtkFastDelaunay3D::EndPointInsertion()
{
  this->Insertion.reset();
}

void vtkFastDelaunay3D::SetClamped(double& property, double value, double lo, double hi, double nan)
{
  value = std::isnan(value) ? nan : std::min(std::max(value, lo), hi); // NaN passes comparisons
  if (property != value)
  {
    property = value;
    this->Modified();
  }
}

void vtkFastDelaunay3D::SetAlpha(double alpha)
{
  this->SetClamped(this->Alpha, alpha, 0.0, VTK_DOUBLE_MAX, 0.0);
}

void vtkFastDelaunay3D::SetTolerance(double tolerance)
{
  this->SetClamped(this->Tolerance, tolerance, 0.0, 1.0, 0.0);
}

void vtkFastDelaunay3D::SetOffset(double offset)
{
  this->SetClamped(this->Offset, offset, 2.5, VTK_DOUBLE_MAX, 2.5);
}

void vtkFastDelaunay3D::SetGridResolution(double pointsPerCell)
{
  this->SetClamped(this->GridResolution, pointsPerCell, 0.0, 1000.0, 4.0);
}

void vtkFastDelaunay3D::SetVolumeThreshold(double threshold)
{
  this->SetClamped(this->VolumeThreshold, threshold, 0.0, 1.0, 0.0);
}

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
  this->RecordFigures(fd3::Statistics());
  const vtkIdType numberOfPoints = input ? input->GetNumberOfPoints() : 0;
  if (numberOfPoints == 0)
  {
    // Under MPI a rank may hold an empty piece: nothing to report there.
    vtkInformation* outInfo = outputVector->GetInformationObject(0);
    if (outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) <= 1)
    {
      vtkWarningMacro("Cannot triangulate; no input points");
    }
    // As vtkDelaunay3D's: no points object at all, whatever the precision asked for.
    output->Initialize();
    if (input)
    {
      output->GetPointData()->PassData(input->GetPointData());
    }
    SetCells(output, {});
    return 1;
  }

  vtkDataArray* weightArray =
    fd3vtk::WeightsChosen(this) ? this->GetInputArrayToProcess(0, inputVector) : nullptr;
  if (fd3vtk::AnyPeriodic(this->Periodic))
  {
    return this->TriangulatePeriodic(input, output, weightArray);
  }

  // VTK points in -> Core -> VTK cells out. The kernel triangulates the output's own coordinates,
  // so the result is exact for what is written.
  vtkSmartPointer<vtkPoints> points =
    PointsInPrecision(input, this->OutputPointsPrecision, this->BoundingTriangulation ? 6 : 0);
  std::vector<double> converted;
  const double* xyz = CoordinatesAsDoubles(points, converted);
  const fd3::Bounds bounds = fd3::finiteBounds(
    xyz, static_cast<std::size_t>(numberOfPoints), ThreadCount(this->NumberOfThreads));
  if (this->BoundingTriangulation)
  {
    SetOctahedron(points, numberOfPoints, bounds, this->Offset);
    xyz = CoordinatesAsDoubles(points, converted); // the octahedron in the output's precision
  }
  const std::size_t count = static_cast<std::size_t>(points->GetNumberOfPoints());
  vtkPointData* pointData = this->BoundingTriangulation ? nullptr : input->GetPointData();
  std::vector<double> weights;
  if (!this->ReadWeights(weightArray, numberOfPoints, count, weights))
  {
    SetPointsWithoutCells(output, points, pointData);
    return 0;
  }
  const double* weightOf = weights.empty() ? nullptr : weights.data();
  fd3::Triangulation result;
  int done = 0;
  if (!KernelRan(
        this, [&] { return this->Triangulate(xyz, weightOf, count, numberOfPoints, bounds); },
        result, output, points, pointData, done))
  {
    return done;
  }
  this->RecordFigures(result.stats);
  if (result.status == fd3::Status::CheckFailed)
  {
    vtkErrorMacro("The kernel's mesh check failed (a bug; please report it with the input): "
      << result.checkReport);
    SetPointsWithoutCells(output, points, pointData);
    return 0;
  }
  if (!this->ReportOnInput(result.status, result.stats, numberOfPoints, weightOf != nullptr))
  {
    SetPointsWithoutCells(output, points, pointData);
    return 1;
  }

  const auto conversionStart = std::chrono::steady_clock::now();
  output->SetPoints(points);
  if (pointData)
  {
    output->GetPointData()->PassData(pointData);
  }
  std::vector<double> density; // before the cells take the tetrahedra over
  if (this->ComputeDensity)
  {
    density = fd3::densities(xyz, count, result);
  }
  this->SetOutputCells(output, xyz, weightOf, count, result);
  this->AddCellArrays(output, xyz);
  if (this->ComputeDensity)
  {
    AddDensity(output, density);
  }
  this->OutputSeconds +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - conversionStart).count();
  this->AddFigures(output->GetFieldData());
  return 1;
}

bool vtkFastDelaunay3D::ReadWeights(
  vtkDataArray* array, vtkIdType inputPoints, std::size_t count, std::vector<double>& weights)
{
  if (!array)
  {
    return true;
  }
  std::string problem;
  weights = fd3vtk::PointWeights(array, inputPoints, this->WeightsAreRadii, count, problem);
  if (weights.empty())
  {
    vtkErrorMacro(
      "Cannot triangulate: " << problem << "; the output holds the points and no cells");
    return false;
  }
  return true;
}

int vtkFastDelaunay3D::TriangulatePeriodic(
  vtkDataSet* input, vtkUnstructuredGrid* output, vtkDataArray* weightArray)
{
  vtkSmartPointer<vtkPoints> points = PointsInPrecision(input, this->OutputPointsPrecision);
  vtkPointData* pointData = input->GetPointData();
  std::vector<double> converted;
  const double* xyz = CoordinatesAsDoubles(points, converted);
  const std::size_t count = static_cast<std::size_t>(points->GetNumberOfPoints());
  std::vector<double> weights;
  if (!this->ReadWeights(weightArray, input->GetNumberOfPoints(), count, weights))
  {
    SetPointsWithoutCells(output, points, pointData);
    return 0;
  }
  const double* weightOf = weights.empty() ? nullptr : weights.data();
  const fd3::Bounds bounds = fd3::finiteBounds(xyz, count, ThreadCount(this->NumberOfThreads));
  const fd3::PeriodicBox box = fd3vtk::PeriodicBoxOf(
    fd3vtk::BoxInUse(this, this->UseInputBounds, this->Bounds, bounds), this->Periodic);
  const std::string problem = fd3vtk::PeriodicBoxProblem(box);
  if (!problem.empty())
  {
    vtkWarningMacro(
      "Cannot triangulate: " << problem << "; the output holds the points and no cells");
    SetPointsWithoutCells(output, points, pointData);
    return 1;
  }
  fd3::PeriodicTriangulation result;
  fd3::PeriodicPlacement placement;
  auto run = [&] {
    fd3::PeriodicTriangulation t =
      fd3::triangulatePeriodic(xyz, weightOf, count, box, this->KernelOptions(bounds.diagonal()));
    if (t.status == fd3::Status::Ok)
    {
      placement = fd3::placePeriodic(xyz, count, t, box);
    }
    return t;
  };
  int done = 0;
  if (!KernelRan(this, run, result, output, points, pointData, done))
  {
    return done;
  }
  this->RecordFigures(result.stats);
  if (!this->ReportOnInput(
        result.status, result.stats, static_cast<vtkIdType>(count), weightOf != nullptr))
  {
    SetPointsWithoutCells(output, points, pointData);
    return 1;
  }

  const auto conversionStart = std::chrono::steady_clock::now();
  this->SetPeriodicOutput(output, points, pointData, xyz, placement,
    this->ComputeDensity ? fd3::densities(xyz, count, result, placement) : std::vector<double>(),
    nullptr, nullptr, weightOf, result.hidden);
  this->OutputSeconds +=
    std::chrono::duration<double>(std::chrono::steady_clock::now() - conversionStart).count();
  this->AddFigures(output->GetFieldData());
  return 1;
}

void vtkFastDelaunay3D::SetPeriodicOutput(vtkUnstructuredGrid* output, vtkPoints* points,
  vtkPointData* pointData, const double* xyz, fd3::PeriodicPlacement& placement,
  std::vector<double> density, const std::uint32_t* ids, const std::vector<std::uint8_t>* owned,
  const double* weights, const std::vector<std::uint32_t>& hidden)
{
  const std::size_t count = static_cast<std::size_t>(points->GetNumberOfPoints());
  const std::size_t images = placement.numberOfImages();
  SetPointsAndImages(output, points, placement);
  SetPointDataAndImages(
    output->GetPointData(), pointData, static_cast<vtkIdType>(count), placement, ids);
  std::vector<double> converted;
  const double* placed = CoordinatesAsDoubles(output->GetPoints(), converted);
  if (this->ComputeDensity)
  {
    std::vector<double> all(count + images);
    std::copy_n(density.begin(), count, all.begin());
    for (std::size_t k = 0; k < images; ++k)
    {
      all[count + k] = density[placement.imageSources[k]];
    }
    AddDensity(output, all);
  }
  if (this->Alpha > 0)
  {
    fd3::AlphaComplex shape = fd3::alphaComplex(
      xyz, weights, count, placement, hidden, this->Alpha, ThreadCount(this->NumberOfThreads));
    if (owned)
    {
      KeepOwned(shape, placement, count, ids, *owned);
    }
    this->SetAlphaShape(output, placement.tetrahedra.data(), shape);
  }
  else
  {
    SetTetrahedra(output, std::move(placement.tetrahedra));
  }
  this->AddCellArrays(output, placed);
}

fd3::Triangulation vtkFastDelaunay3D::Triangulate(const double* xyz, const double* weights,
  std::size_t count, vtkIdType inputPoints, const fd3::Bounds& bounds)
{
  const fd3::Options options = this->KernelOptions(bounds.diagonal());
  const std::vector<vtkIdType> mergedInto =
    this->Locator ? this->MergeByLocator(xyz, inputPoints, bounds) : std::vector<vtkIdType>();
  const std::size_t merged = static_cast<std::size_t>(
    std::count_if(mergedInto.begin(), mergedInto.end(), [](vtkIdType to) { return to >= 0; }));
  if (merged == 0)
  {
    return fd3::triangulate(xyz, weights, count, options);
  }
  // The kernel leaves out what it cannot place: the merged points, as NaN in a copy.
  std::vector<double> kept(xyz, xyz + 3 * count);
  for (std::size_t i = 0; i < mergedInto.size(); ++i)
  {
    if (mergedInto[i] >= 0)
    {
      std::fill_n(&kept[3 * i], 3, std::numeric_limits<double>::quiet_NaN());
    }
  }
  fd3::Triangulation result = fd3::triangulate(kept.data(), weights, count, options);
  // They were merged, not invalid: counted with the skipped points, each represented by the point
  // it was merged into (which Density counts them at).
  result.stats.nonFinitePoints -= merged;
  result.stats.closePointsSkipped += merged;
  for (std::size_t i = 0; i < mergedInto.size() && !result.representative.empty(); ++i)
  {
    if (mergedInto[i] >= 0)
    {
      result.representative[i] = result.representative[static_cast<std::size_t>(mergedInto[i])];
    }
  }
  return result;
}

std::vector<vtkIdType> vtkFastDelaunay3D::MergeByLocator(
  const double* xyz, vtkIdType count, const fd3::Bounds& box)
{
  std::vector<vtkIdType> mergedInto(static_cast<std::size_t>(count), -1);
  if (box.empty())
  {
    return mergedInto;
  }
  double bounds[6];
  box.toMinMax(bounds);
  vtkNew<vtkPoints> inserted;
  inserted->SetDataType(VTK_DOUBLE);
  this->Locator->InitPointInsertion(inserted, bounds);
  std::vector<vtkIdType> inputId; // of each point inserted into the locator
  for (vtkIdType i = 0; i < count; ++i)
  {
    const double* x = xyz + 3 * i;
    if (!fd3::isFinite(x))
    {
      continue;
    }
    const vtkIdType near = this->Locator->IsInsertedPoint(x);
    if (near >= 0)
    {
      mergedInto[static_cast<std::size_t>(i)] = inputId[static_cast<std::size_t>(near)];
      continue;
    }
    this->Locator->InsertPoint(static_cast<vtkIdType>(inputId.size()), x);
    inputId.push_back(i);
  }
  this->Locator->Initialize(); // its buckets are not needed any more
  return mergedInto;
}

fd3::Options vtkFastDelaunay3D::KernelOptions(double diagonal)
{
  fd3::Options options;
  options.pointsPerCell = this->GridResolution;
  options.volumeThreshold = this->VolumeThreshold;
  options.tolerance = this->Tolerance * diagonal;
  switch (this->InsertionOrder)
  {
    case INPUT_ORDER:
      options.order = fd3::InsertionOrder::Input;
      break;
    case RANDOM_ORDER:
      options.order = fd3::InsertionOrder::Random;
      break;
    default:
      options.order = fd3::InsertionOrder::Brio;
      break;
  }
  options.randomSeed = static_cast<std::uint64_t>(this->RandomSeed);
  options.threads = ThreadCount(this->NumberOfThreads);
  options.computeNeighbors = this->Alpha > 0; // the alpha complex walks across faces
  options.progress = [this](double fraction) {
    this->UpdateProgress(fraction);
    return !fd3vtk::AbortRequested(this);
  };
  return options;
}

void vtkFastDelaunay3D::RecordFigures(const fd3::Statistics& stats)
{
  this->NumberOfInsertedPoints = static_cast<vtkIdType>(stats.insertedPoints);
  this->NumberOfDuplicatePoints = static_cast<vtkIdType>(stats.duplicatesMerged);
  this->NumberOfSkippedPoints = static_cast<vtkIdType>(stats.closePointsSkipped);
  this->NumberOfInvalidPoints = static_cast<vtkIdType>(stats.nonFinitePoints);
  this->NumberOfHiddenPoints = static_cast<vtkIdType>(stats.hiddenPoints);
  this->NumberOfTetrahedra = static_cast<vtkIdType>(stats.tetrahedra);
  this->MeanWalkLength = stats.meanWalk();
  this->MaxWalkLength = static_cast<vtkIdType>(stats.maxWalkSteps);
  this->MeanCavitySize = stats.meanCavity();
  this->KernelSeconds = stats.secondsTotal;
  this->SortSeconds = stats.secondsSort;
  this->LocateSeconds = stats.secondsLocate;
  this->CavitySeconds = stats.secondsCavity;
  this->FillSeconds = stats.secondsFill;
  this->OutputSeconds = stats.secondsOutput;
}

bool vtkFastDelaunay3D::ReportOnInput(
  fd3::Status status, const fd3::Statistics& stats, vtkIdType numberOfPoints, bool weighted)
{
  const std::string leftOut = LeftOutPoints(stats, weighted);
  if (status != fd3::Status::Ok)
  {
    vtkWarningMacro("Cannot triangulate: "
      << fd3::toString(status) << "; the output holds the points and no cells"
      << (leftOut.empty() ? "" : " (left out: ") << leftOut << (leftOut.empty() ? "" : ")"));
    return false;
  }
  if (!leftOut.empty())
  {
    const std::size_t unused =
      stats.duplicatesMerged + stats.closePointsSkipped + stats.nonFinitePoints;
    vtkWarningMacro(<< unused << " of " << numberOfPoints
                    << " points are not vertices of the tetrahedralization (they remain in the "
                       "output, unused): "
                    << leftOut);
  }
  return true;
}

void vtkFastDelaunay3D::SetOutputCells(vtkUnstructuredGrid* output, const double* xyz,
  const double* weights, std::size_t count, fd3::Triangulation& result, const CellFilter& keep)
{
  if (this->Alpha <= 0)
  {
    fd3::IdArray& tets = result.tetrahedra;
    if (keep)
    {
      KeepCells(tets, 4, [&](const std::uint32_t* ids) { return keep(ids, 4); });
      fd3::releaseSpareCapacity(tets);
    }
    SetTetrahedra(output, std::move(tets));
    tets = fd3::IdArray();
    return;
  }
  const std::uint32_t* tets = result.tetrahedra.data();
  fd3::AlphaComplex shape =
    fd3::alphaComplex(xyz, weights, count, result, this->Alpha, ThreadCount(this->NumberOfThreads));
  if (keep)
  {
    KeepCells(shape.tetrahedra, 1, [&](const std::uint32_t* t) { return keep(tets + 4 * *t, 4); });
    KeepCells(shape.triangles, 3, [&](const std::uint32_t* ids) { return keep(ids, 3); });
    KeepCells(shape.lines, 2, [&](const std::uint32_t* ids) { return keep(ids, 2); });
    KeepCells(shape.vertices, 1, [&](const std::uint32_t* ids) { return keep(ids, 1); });
  }
  this->SetAlphaShape(output, tets, shape);
}

void vtkFastDelaunay3D::SetAlphaShape(
  vtkUnstructuredGrid* output, const std::uint32_t* tets, const fd3::AlphaComplex& shape)
{
  std::vector<CellBlock> blocks; // in vtkDelaunay3D's order
  if (this->AlphaTris)
  {
    blocks.push_back(
      { VTK_TRIANGLE, 3, shape.triangles.data(), nullptr, shape.triangles.size() / 3 });
  }
  if (this->AlphaLines)
  {
    blocks.push_back({ VTK_LINE, 2, shape.lines.data(), nullptr, shape.lines.size() / 2 });
  }
  if (this->AlphaVerts)
  {
    blocks.push_back({ VTK_VERTEX, 1, shape.vertices.data(), nullptr, shape.vertices.size() });
  }
  if (this->AlphaTets)
  {
    blocks.push_back({ VTK_TETRA, 4, tets, shape.tetrahedra.data(), shape.tetrahedra.size() });
  }
  SetCells(output, blocks);
}

void vtkFastDelaunay3D::AddCellArrays(vtkUnstructuredGrid* output, const double* xyz)
{
  if (this->ComputeCircumradius || this->ComputeVolume || this->ComputeRadiusEdgeRatio)
  {
    AddCellMeasures(
      output, xyz, this->ComputeCircumradius, this->ComputeVolume, this->ComputeRadiusEdgeRatio);
  }
}

void vtkFastDelaunay3D::AddDensity(vtkUnstructuredGrid* output, const std::vector<double>& density)
{
  auto array = fd3vtk::NamedArray<vtkDoubleArray>("Density", output->GetNumberOfPoints());
  for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
  {
    array->SetValue(i,
      static_cast<std::size_t>(i) < density.size() ? density[i]
                                                   : std::numeric_limits<double>::quiet_NaN());
  }
  output->GetPointData()->RemoveArray("Density");
  output->GetPointData()->AddArray(array);
}

void vtkFastDelaunay3D::AddFigures(vtkFieldData* fields) const
{
  // The counts of left-out points always travel with the data that lacks them.
  const bool leftOut = this->NumberOfDuplicatePoints > 0 || this->NumberOfSkippedPoints > 0 ||
    this->NumberOfInvalidPoints > 0 || this->NumberOfHiddenPoints > 0;
  for (const Figure& figure : this->Figures())
  {
    if (this->ComputeStatistics || (leftOut && figure.CountsLeftOutPoints))
    {
      AddFieldValue(fields, figure.Name, figure.Value);
    }
  }
}

std::vector<vtkFastDelaunay3D::Figure> vtkFastDelaunay3D::Figures() const
{
  return { { "NumberOfInsertedPoints", static_cast<double>(this->NumberOfInsertedPoints), false },
    { "NumberOfDuplicatePoints", static_cast<double>(this->NumberOfDuplicatePoints), true },
    { "NumberOfSkippedPoints", static_cast<double>(this->NumberOfSkippedPoints), true },
    { "NumberOfInvalidPoints", static_cast<double>(this->NumberOfInvalidPoints), true },
    { "NumberOfHiddenPoints", static_cast<double>(this->NumberOfHiddenPoints), true },
    { "NumberOfTetrahedra", static_cast<double>(this->NumberOfTetrahedra), false },
    { "MeanWalkLength", this->MeanWalkLength, false },
    { "MaxWalkLength", static_cast<double>(this->MaxWalkLength), false },
    { "MeanCavitySize", this->MeanCavitySize, false },
    { "KernelSeconds", this->KernelSeconds, false }, { "SortSeconds", this->SortSeconds, false },
    { "LocateSeconds", this->LocateSeconds, false },
    { "CavitySeconds", this->CavitySeconds, false }, { "FillSeconds", this->FillSeconds, false },
    { "OutputSeconds", this->OutputSeconds, false } };
}

void vtkFastDelaunay3D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Alpha: " << this->Alpha << "\n";
  os << indent << "Alpha Tets: " << (this->AlphaTets ? "On\n" : "Off\n");
  os << indent << "Alpha Tris: " << (this->AlphaTris ? "On\n" : "Off\n");
  os << indent << "Alpha Lines: " << (this->AlphaLines ? "On\n" : "Off\n");
  os << indent << "Alpha Verts: " << (this->AlphaVerts ? "On\n" : "Off\n");
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "Offset: " << this->Offset << "\n";
  os << indent << "Bounding Triangulation: " << (this->BoundingTriangulation ? "On\n" : "Off\n");
  if (this->Locator)
  {
    os << indent << "Locator: " << this->Locator << "\n";
  }
  else
  {
    os << indent << "Locator: (none)\n";
  }
  os << indent << "Output Points Precision: " << this->OutputPointsPrecision << "\n";
  os << indent << "GridResolution: " << this->GridResolution << "\n";
  os << indent << "VolumeThreshold: " << this->VolumeThreshold << "\n";
  os << indent << "InsertionOrder: " << this->InsertionOrder << "\n";
  os << indent << "RandomSeed: " << this->RandomSeed << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ComputeCircumradius: " << this->ComputeCircumradius << "\n";
  os << indent << "ComputeVolume: " << this->ComputeVolume << "\n";
  os << indent << "ComputeDensity: " << this->ComputeDensity << "\n";
  os << indent << "ComputeRadiusEdgeRatio: " << this->ComputeRadiusEdgeRatio << "\n";
  os << indent << "ComputeStatistics: " << this->ComputeStatistics << "\n";
  os << indent << "WeightsAreRadii: " << this->WeightsAreRadii << "\n";
  os << indent << "Periodic: " << this->Periodic[0] << " " << this->Periodic[1] << " "
     << this->Periodic[2] << "\n";
  os << indent << "UseInputBounds: " << this->UseInputBounds << "\n";
  os << indent << "Bounds: " << this->Bounds[0] << " " << this->Bounds[1] << " " << this->Bounds[2]
     << " " << this->Bounds[3] << " " << this->Bounds[4] << " " << this->Bounds[5] << "\n";
  for (const Figure& figure : this->Figures())
  {
    os << indent << figure.Name << ": " << figure.Value << "\n";
  }
}
