/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "vtkFastDelaunay3D.h"

#include "FilterArrays.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkSMPThreadLocalObject.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Delaunay.h"
#include "fd3/Measures.h"

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

/// The input's points in the requested precision, with room for `extra` more after them: the
/// input's own array when nothing changes (shared, same ids), else a copy.
vtkSmartPointer<vtkPoints> PointsInPrecision(vtkDataSet* input, int precision, vtkIdType extra)
{
  auto* pointSet = vtkPointSet::SafeDownCast(input);
  vtkPoints* given = pointSet ? pointSet->GetPoints() : nullptr;
  int type = given ? given->GetDataType() : VTK_DOUBLE;
  if (precision == vtkAlgorithm::SINGLE_PRECISION)
  {
    type = VTK_FLOAT;
  }
  else if (precision == vtkAlgorithm::DOUBLE_PRECISION)
  {
    type = VTK_DOUBLE;
  }
  if (given && type == given->GetDataType() && extra == 0)
  {
    return given;
  }
  const vtkIdType n = input ? input->GetNumberOfPoints() : 0;
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(type);
  points->SetNumberOfPoints(n + extra);
  vtkSMPTools::For(0, n, [&](vtkIdType begin, vtkIdType end) {
    double x[3];
    for (vtkIdType i = begin; i < end; ++i)
    {
      input->GetPoint(i, x);
      points->SetPoint(i, x);
    }
  });
  return points;
}

/// The output's points: the input's own when nothing changes (shared, same ids), else a copy in
/// the requested precision, followed by the bounding octahedron's 6 points when asked for.
vtkSmartPointer<vtkPoints> MakeOutputPoints(
  vtkDataSet* input, const double bounds[6], int precision, bool bounding, double offset)
{
  vtkSmartPointer<vtkPoints> points = PointsInPrecision(input, precision, bounding ? 6 : 0);
  if (bounding) // vtkDelaunay3D's octahedron: centre +- offset * diagonal along each axis
  {
    const vtkIdType n = input->GetNumberOfPoints();
    double centre[3], farthest = 0;
    for (int a = 0; a < 3; ++a)
    {
      centre[a] = bounds[2 * a] / 2 + bounds[2 * a + 1] / 2;
      farthest = std::max(farthest, std::fabs(centre[a]));
    }
    // No further than VTK_DOUBLE_MAX - |centre| (halved against the rounding of the sum).
    const double diagonal = fd3::diagonal(bounds);
    const double length =
      std::min(offset * (diagonal > 0 ? diagonal : 1.0), (VTK_DOUBLE_MAX - farthest) / 2);
    for (int k = 0; k < 6; ++k)
    {
      double x[3] = { centre[0], centre[1], centre[2] };
      x[k / 2] += (k % 2 ? length : -length);
      points->SetPoint(n + k, x);
    }
  }
  return points;
}

/// Copies x,y,z tuples of any real array into doubles, without a virtual call per tuple.
struct CopyToDoubles
{
  template <typename ArrayType>
  void operator()(ArrayType* array, double* out) const
  {
    const auto tuples = vtk::DataArrayTupleRange<3>(array);
    vtkSMPTools::For(0, tuples.size(), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType i = begin; i < end; ++i)
      {
        for (int k = 0; k < 3; ++k)
        {
          out[3 * i + k] = static_cast<double>(tuples[i][k]);
        }
      }
    });
  }
};

/// A run of cells of one type: cell c is ids[size * (select ? select[c] : c) + k], k < size.
struct CellBlock
{
  int Type;
  int Size;
  const std::uint32_t* Ids;
  const std::uint32_t* Select;
  std::size_t Count;
};

/// The output cells, block after block, written straight into the cell array's offsets and
/// connectivity (no per-cell calls); 32-bit storage whenever the ids fit, which halves its memory.
template <typename IdArray>
void SetCells(vtkUnstructuredGrid* output, const std::vector<CellBlock>& blocks)
{
  using Id = typename IdArray::ValueType;
  vtkIdType cells = 0, size = 0;
  for (const CellBlock& b : blocks)
  {
    cells += static_cast<vtkIdType>(b.Count);
    size += static_cast<vtkIdType>(b.Count) * b.Size;
  }
  vtkNew<IdArray> offsets, connectivity;
  vtkNew<vtkUnsignedCharArray> types;
  offsets->SetNumberOfValues(cells + 1);
  connectivity->SetNumberOfValues(size);
  types->SetNumberOfValues(cells);
  vtkIdType firstCell = 0, firstId = 0;
  for (const CellBlock& b : blocks)
  {
    Id* offset = offsets->GetPointer(firstCell);
    Id* ids = connectivity->GetPointer(firstId);
    std::fill_n(types->GetPointer(firstCell), b.Count, static_cast<unsigned char>(b.Type));
    vtkSMPTools::For(0, static_cast<vtkIdType>(b.Count), [&](vtkIdType begin, vtkIdType end) {
      for (vtkIdType c = begin; c < end; ++c)
      {
        const std::size_t source = b.Size * std::size_t(b.Select ? b.Select[c] : c);
        offset[c] = static_cast<Id>(firstId + b.Size * c);
        for (int k = 0; k < b.Size; ++k)
        {
          ids[b.Size * c + k] = static_cast<Id>(b.Ids[source + k]);
        }
      }
    });
    firstCell += static_cast<vtkIdType>(b.Count);
    firstId += static_cast<vtkIdType>(b.Count) * b.Size;
  }
  offsets->SetValue(cells, static_cast<Id>(size));
  vtkNew<vtkCellArray> cellArray;
  cellArray->SetData(offsets, connectivity);
  output->SetCells(types, cellArray);
}

void SetCells(vtkUnstructuredGrid* output, const std::vector<CellBlock>& blocks)
{
  std::size_t size = 0;
  for (const CellBlock& b : blocks)
  {
    size += b.Count * b.Size;
  }
  if (size < static_cast<std::size_t>(std::numeric_limits<vtkTypeInt32>::max()))
  {
    SetCells<vtkTypeInt32Array>(output, blocks);
  }
  else
  {
    SetCells<vtkTypeInt64Array>(output, blocks);
  }
}

/// Memory of the kernel's allocator becomes an output array without a copy: the kernel's
/// tetrahedra its 32-bit connectivity (a copy would hold both at once, 16 bytes per tetrahedron,
/// 108 per point on uniform points), and the offsets and types, written in the kernel's allocator
/// (which does not zero them first). VTK frees an array's memory through a plain function of its
/// address, so each vector waits here, by that address, until VTK lets it go.
class HandedOver
{
public:
  template <typename Array, typename T>
  static void Into(Array* array, std::vector<T, fd3::BulkAllocator<T>> values)
  {
    static_assert(sizeof(T) == sizeof(typename Array::ValueType), "values are taken as they are");
    auto held = std::make_shared<std::vector<T, fd3::BulkAllocator<T>>>(std::move(values));
    auto* data = reinterpret_cast<typename Array::ValueType*>(held->data());
    const auto size = static_cast<vtkIdType>(held->size());
    {
      std::lock_guard<std::mutex> lock(Mutex());
      Held().emplace(data, std::move(held));
    }
    array->SetArray(data, size, 0, Array::VTK_DATA_ARRAY_USER_DEFINED);
    array->SetArrayFreeFunction(&HandedOver::Free);
  }

private:
  static void Free(void* data)
  {
    std::shared_ptr<void> released; // destroyed outside the lock
    std::lock_guard<std::mutex> lock(Mutex());
    const auto it = Held().find(data);
    if (it != Held().end())
    {
      released = std::move(it->second);
      Held().erase(it);
    }
  }
  // Never destroyed: an output may outlive the statics of this library.
  static std::mutex& Mutex()
  {
    static auto* mutex = new std::mutex;
    return *mutex;
  }
  static std::map<void*, std::shared_ptr<void>>& Held()
  {
    static auto* held = new std::map<void*, std::shared_ptr<void>>;
    return *held;
  }
};

/// Tetrahedra only (4 ids each): the connectivity is `tets` itself where its ids fit 32 bits.
void SetTetrahedra(vtkUnstructuredGrid* output, fd3::IdArray tets)
{
  const std::size_t cells = tets.size() / 4;
  if (cells == 0 ||
    tets.size() >= static_cast<std::size_t>(std::numeric_limits<vtkTypeInt32>::max()))
  {
    SetCells(output, { { VTK_TETRA, 4, tets.data(), nullptr, cells } });
    return;
  }
  std::vector<vtkTypeInt32, fd3::BulkAllocator<vtkTypeInt32>> offset(cells + 1);
  std::vector<unsigned char, fd3::BulkAllocator<unsigned char>> type(cells);
  vtkSMPTools::For(0, static_cast<vtkIdType>(cells) + 1, [&offset](vtkIdType begin, vtkIdType end) {
    for (vtkIdType c = begin; c < end; ++c)
    {
      offset[c] = static_cast<vtkTypeInt32>(4 * c);
    }
  });
  std::fill(type.begin(), type.end(), static_cast<unsigned char>(VTK_TETRA));
  vtkNew<vtkTypeInt32Array> offsets, connectivity;
  vtkNew<vtkUnsignedCharArray> types;
  HandedOver::Into(offsets.Get(), std::move(offset));
  HandedOver::Into(types.Get(), std::move(type));
  // Ids below 2^31 (checked above) read the same as signed values.
  HandedOver::Into(connectivity.Get(), std::move(tets));
  vtkNew<vtkCellArray> cellArray;
  cellArray->SetData(offsets, connectivity);
  output->SetCells(types, cellArray);
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
      vtkIdType size;
      const vtkIdType* ids;
      output->GetCells()->GetCellAtId(c, size, ids, idList);
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

/// Removes in place the cells of `size` values each that `keep` refuses, keeping the order.
template <typename Values, typename Keep>
void KeepCells(Values& values, int size, Keep keep)
{
  std::size_t kept = 0;
  for (std::size_t c = 0; c + size <= values.size(); c += size)
  {
    if (keep(values.data() + c))
    {
      std::copy_n(values.begin() + c, size, values.begin() + kept);
      kept += size;
    }
  }
  values.resize(kept);
}

/// What the tetrahedralization leaves out, by cause, with what keeps it; empty when nothing is.
std::string LeftOutPoints(const fd3::Statistics& stats)
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
           << " with NaN or infinite coordinates (no position to triangulate)";
  }
  return causes.str();
}

using fd3vtk::AddFieldValue;
} // namespace

vtkFastDelaunay3D::vtkFastDelaunay3D() = default;

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

void vtkFastDelaunay3D::SetPointsWithoutCells(
  vtkUnstructuredGrid* output, vtkPoints* points, vtkPointData* pointData)
{
  output->Initialize();
  output->SetPoints(points ? points : vtkSmartPointer<vtkPoints>::New().Get());
  if (pointData)
  {
    output->GetPointData()->PassData(pointData);
  }
  SetCells(output, {});
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
    SetPointsWithoutCells(output, nullptr, input ? input->GetPointData() : nullptr);
    return 1;
  }

  // VTK points in -> Core -> VTK cells out. The kernel triangulates the output's own coordinates,
  // so the result is exact for what is written.
  double bounds[6];
  BoundsOfFinitePoints(input, bounds);
  vtkSmartPointer<vtkPoints> points = MakeOutputPoints(
    input, bounds, this->OutputPointsPrecision, this->BoundingTriangulation, this->Offset);
  std::vector<double> converted;
  const double* xyz = CoordinatesAsDoubles(points, converted);
  const std::size_t count = static_cast<std::size_t>(points->GetNumberOfPoints());
  vtkPointData* pointData = this->BoundingTriangulation ? nullptr : input->GetPointData();
  fd3::Triangulation result;
  try
  {
    result = fd3::triangulate(xyz, count, this->KernelOptions(fd3::diagonal(bounds)));
  }
  catch (const std::exception& failure) // out of memory, or more points than 32-bit ids hold
  {
    vtkErrorMacro(
      "Triangulation failed: " << failure.what() << "; the output holds the points and no cells");
    SetPointsWithoutCells(output, points, pointData);
    return 0;
  }
  if (result.status == fd3::Status::Aborted)
  {
    output->Initialize();
    return 1;
  }
  this->RecordFigures(result.stats);
  if (result.status == fd3::Status::CheckFailed)
  {
    vtkErrorMacro("The kernel's mesh check failed (a bug; please report it with the input): "
      << result.checkReport);
    SetPointsWithoutCells(output, points, pointData);
    return 0;
  }
  if (!this->ReportOnInput(result.status, result.stats, numberOfPoints))
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
  this->SetOutputCells(output, xyz, count, result);
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
  options.threads = this->ThreadCount();
  options.computeNeighbors = this->Alpha > 0; // the alpha complex walks across faces
  options.progress = [this](double fraction) {
    this->UpdateProgress(fraction);
    return !this->CheckAbort();
  };
  return options;
}

int vtkFastDelaunay3D::ThreadCount() const
{
  return this->NumberOfThreads > 0 ? this->NumberOfThreads
                                   : vtkSMPTools::GetEstimatedNumberOfThreads();
}

void vtkFastDelaunay3D::RecordFigures(const fd3::Statistics& stats)
{
  this->NumberOfInsertedPoints = static_cast<vtkIdType>(stats.insertedPoints);
  this->NumberOfDuplicatePoints = static_cast<vtkIdType>(stats.duplicatesMerged);
  this->NumberOfSkippedPoints = static_cast<vtkIdType>(stats.closePointsSkipped);
  this->NumberOfInvalidPoints = static_cast<vtkIdType>(stats.nonFinitePoints);
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
  fd3::Status status, const fd3::Statistics& stats, vtkIdType numberOfPoints)
{
  const std::string leftOut = LeftOutPoints(stats);
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
  std::size_t count, fd3::Triangulation& result, const CellFilter& keep)
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
  fd3::AlphaComplex shape = fd3::alphaComplex(xyz, count, result, this->Alpha, this->ThreadCount());
  if (keep)
  {
    KeepCells(shape.tetrahedra, 1, [&](const std::uint32_t* t) { return keep(tets + 4 * *t, 4); });
    KeepCells(shape.triangles, 3, [&](const std::uint32_t* ids) { return keep(ids, 3); });
    KeepCells(shape.lines, 2, [&](const std::uint32_t* ids) { return keep(ids, 2); });
    KeepCells(shape.vertices, 1, [&](const std::uint32_t* ids) { return keep(ids, 1); });
  }
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

const double* vtkFastDelaunay3D::CoordinatesAsDoubles(vtkPoints* points, std::vector<double>& copy)
{
  vtkDataArray* data = points->GetData();
  if (auto* doubles = vtkDoubleArray::FastDownCast(data))
  {
    return doubles->GetPointer(0);
  }
  copy.resize(3 * static_cast<std::size_t>(points->GetNumberOfPoints()));
  using Reals = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
  if (!Reals::Execute(data, CopyToDoubles{}, copy.data()))
  {
    CopyToDoubles{}(data, copy.data());
  }
  return copy.data();
}

vtkSmartPointer<vtkPoints> vtkFastDelaunay3D::InputPoints(vtkDataSet* input, int precision)
{
  return PointsInPrecision(input, precision, 0);
}

// NaN or infinite points would spoil VTK's own bounds.
void vtkFastDelaunay3D::BoundsOfFinitePoints(vtkDataSet* input, double bounds[6])
{
  bounds[0] = bounds[2] = bounds[4] = VTK_DOUBLE_MAX;
  bounds[1] = bounds[3] = bounds[5] = -VTK_DOUBLE_MAX;
  double x[3];
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    input->GetPoint(i, x);
    if (fd3::isFinite(x))
    {
      for (int a = 0; a < 3; ++a)
      {
        bounds[2 * a] = std::min(bounds[2 * a], x[a]);
        bounds[2 * a + 1] = std::max(bounds[2 * a + 1], x[a]);
      }
    }
  }
}

void vtkFastDelaunay3D::AddFigures(vtkFieldData* fields) const
{
  // The counts of left-out points always travel with the data that lacks them.
  const bool leftOut = this->NumberOfDuplicatePoints > 0 || this->NumberOfSkippedPoints > 0 ||
    this->NumberOfInvalidPoints > 0;
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
  for (const Figure& figure : this->Figures())
  {
    os << indent << figure.Name << ": " << figure.Value << "\n";
  }
}
