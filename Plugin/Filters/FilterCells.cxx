/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "FilterCells.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Voronoi.h"
#include "fd3/Workers.h"

#include <limits>
#include <map>
#include <memory>
#include <mutex>

namespace
{
using fd3vtk::CellBlock;

/// The output cells, block after block, written straight into the cell array's offsets and
/// connectivity (no per-cell calls); 32-bit storage whenever the ids fit, which halves its memory.
template <typename IdArray>
void WriteCells(vtkUnstructuredGrid* output, const std::vector<CellBlock>& blocks)
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

} // namespace

namespace fd3vtk
{
void SetCells(vtkUnstructuredGrid* output, const std::vector<CellBlock>& blocks)
{
  std::size_t size = 0;
  for (const CellBlock& b : blocks)
  {
    size += b.Count * b.Size;
  }
  if (size < static_cast<std::size_t>(std::numeric_limits<vtkTypeInt32>::max()))
  {
    WriteCells<vtkTypeInt32Array>(output, blocks);
  }
  else
  {
    WriteCells<vtkTypeInt64Array>(output, blocks);
  }
}
} // namespace fd3vtk

namespace
{
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

} // namespace

namespace fd3vtk
{
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

void SetVertexCells(vtkUnstructuredGrid* output, vtkIdType count)
{
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(count + 1);
  connectivity->SetNumberOfValues(count);
  vtkSMPTools::For(0, count, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType c = begin; c < end; ++c)
    {
      offsets->SetValue(c, c);
      connectivity->SetValue(c, c);
    }
  });
  offsets->SetValue(count, count);
  vtkNew<vtkCellArray> vertices;
  vertices->SetData(offsets, connectivity);
  output->SetCells(VTK_VERTEX, vertices);
}

void SetPolyhedra(vtkUnstructuredGrid* output, fd3::VoronoiCells& cells, fd3::Workers& workers)
{
  const std::size_t n = cells.numberOfCells();
  // Where each cell's face stream starts (its face count, then each face's size and ids).
  std::vector<vtkIdType, fd3::BulkAllocator<vtkIdType>> streamAt(n + 1);
  streamAt[0] = 0;
  for (std::size_t c = 0; c < n; ++c)
  {
    const std::size_t faces = cells.numberOfFaces(c);
    const std::size_t ids =
      cells.faceStart[cells.cellFaces[c + 1]] - cells.faceStart[cells.cellFaces[c]];
    streamAt[c + 1] = streamAt[c] + (faces == 0 ? 0 : static_cast<vtkIdType>(1 + faces + ids));
  }
  vtkNew<vtkIdTypeArray> faceLocations, faces;
  vtkNew<vtkUnsignedCharArray> types;
  faceLocations->SetNumberOfValues(static_cast<vtkIdType>(n));
  faces->SetNumberOfValues(streamAt[n]);
  types->SetNumberOfValues(static_cast<vtkIdType>(n));
  vtkIdType* location = faceLocations->GetPointer(0);
  vtkIdType* stream = faces->GetPointer(0);
  unsigned char* type = types->GetPointer(0);
  workers.forRanges(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
    {
      const std::size_t first = cells.cellFaces[c], last = cells.cellFaces[c + 1];
      type[c] = first == last ? VTK_EMPTY_CELL : VTK_POLYHEDRON;
      location[c] = first == last ? -1 : streamAt[c];
      if (first == last)
      {
        continue;
      }
      vtkIdType* at = stream + streamAt[c];
      *at++ = static_cast<vtkIdType>(last - first);
      for (std::size_t f = first; f < last; ++f)
      {
        const std::uint32_t* ids = cells.faceVertices.data() + cells.faceStart[f];
        const std::size_t size = cells.faceStart[f + 1] - cells.faceStart[f];
        *at++ = static_cast<vtkIdType>(size);
        at = std::copy(ids, ids + size, at);
      }
    }
  });
  // Each cell's points, each once, as the kernel lists them: its own ids handed over where they fit
  // 32 bits (as the tetrahedra are), beside offsets of the same width.
  vtkNew<vtkCellArray> polyhedra;
  const fd3::VoronoiCells::Offsets& pointStart = cells.cellPointStart;
  if (cells.cellPoints.size() < static_cast<std::size_t>(std::numeric_limits<vtkTypeInt32>::max()))
  {
    vtkNew<vtkTypeInt32Array> offsets, connectivity;
    offsets->SetNumberOfValues(static_cast<vtkIdType>(n + 1));
    vtkTypeInt32* offset = offsets->GetPointer(0);
    workers.forRanges(n + 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c)
      {
        offset[c] = static_cast<vtkTypeInt32>(pointStart[c]);
      }
    });
    HandedOver::Into(connectivity.Get(), std::move(cells.cellPoints));
    polyhedra->SetData(offsets, connectivity);
  }
  else
  {
    vtkNew<vtkTypeInt64Array> offsets, connectivity;
    offsets->SetNumberOfValues(static_cast<vtkIdType>(n + 1));
    connectivity->SetNumberOfValues(static_cast<vtkIdType>(cells.cellPoints.size()));
    std::copy(pointStart.begin(), pointStart.end(), offsets->GetPointer(0));
    std::copy(cells.cellPoints.begin(), cells.cellPoints.end(), connectivity->GetPointer(0));
    fd3::IdArray().swap(cells.cellPoints);
    polyhedra->SetData(offsets, connectivity);
  }
  output->SetCells(types, polyhedra, faceLocations, faces);
}

vtkSmartPointer<vtkPoints> PointsOf(fd3::VoronoiCells::Doubles xyz)
{
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  HandedOver::Into(coordinates.Get(), std::move(xyz));
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(coordinates);
  return points;
}

void SetPointsWithoutCells(vtkUnstructuredGrid* output, vtkPoints* points, vtkPointData* pointData)
{
  output->Initialize();
  output->SetPoints(points ? points : vtkSmartPointer<vtkPoints>::New().Get());
  if (pointData)
  {
    output->GetPointData()->PassData(pointData);
  }
  SetCells(output, {});
}
} // namespace fd3vtk
