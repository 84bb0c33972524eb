/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// How the filters of FastDelaunay3D (and their MPI subclasses) write the kernel's cells into VTK's
// arrays: runs of simplices, the tetrahedra themselves without a copy, the Voronoi polyhedra, and
// the output of no cells. Shared by the module's filters; not an API of its own.
#ifndef FilterCells_h
#define FilterCells_h

#include "FastDelaunay3DFiltersModule.h" // For export macro
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "fd3/Delaunay.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

class vtkPointData;
class vtkPoints;
class vtkUnstructuredGrid;
namespace fd3
{
struct VoronoiCells;
class Workers;
} // namespace fd3

namespace fd3vtk
{
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
FASTDELAUNAY3DFILTERS_EXPORT void SetCells(
  vtkUnstructuredGrid* output, const std::vector<CellBlock>& blocks);

/// Tetrahedra only (4 ids each): the connectivity is `tets` itself where its ids fit 32 bits, the
/// kernel's memory handed over to VTK without a copy.
FASTDELAUNAY3DFILTERS_EXPORT void SetTetrahedra(vtkUnstructuredGrid* output, fd3::IdArray tets);

/// One VTK_VERTEX cell per point, cell c at point c.
FASTDELAUNAY3DFILTERS_EXPORT void SetVertexCells(vtkUnstructuredGrid* output, vtkIdType count);

/// The cells' polyhedra: cell c is a VTK_POLYHEDRON on cells.points (VTK_EMPTY_CELL where it has
/// no face), its face stream as VTK stores it and its points (cells.cellPoints, handed over: empty
/// on return) as connectivity. Written on `workers`' threads.
FASTDELAUNAY3DFILTERS_EXPORT void SetPolyhedra(
  vtkUnstructuredGrid* output, fd3::VoronoiCells& cells, fd3::Workers& workers);

/// Points whose coordinates are `xyz` itself (x, y, z each), the kernel's memory handed over to
/// VTK without a copy.
FASTDELAUNAY3DFILTERS_EXPORT vtkSmartPointer<vtkPoints> PointsOf(
  std::vector<double, fd3::BulkAllocator<double>> xyz);

/// The points and point data with an empty cell array: the output where no cell exists (fewer
/// than 4 distinct points, all coplanar, a failure), as vtkDelaunay3D's; the cell array keeps it a
/// dataset that every writer writes and reads back.
FASTDELAUNAY3DFILTERS_EXPORT void SetPointsWithoutCells(
  vtkUnstructuredGrid* output, vtkPoints* points, vtkPointData* pointData);

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
} // namespace fd3vtk

#endif
