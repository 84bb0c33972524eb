/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// vtkFastDelaunay3D's incremental API (InitPointInsertion, InsertPoint), on the exact kernel: the
// kernel's mesh of a bounding octahedron and the points inserted so far, and the caller's
// vtkUnstructuredGrid kept as its mirror after every point. A private header of the module.
#ifndef PointInsertion_h
#define PointInsertion_h

#include "vtkType.h"

#include "fd3/Distributed.h"

#include <vector>

class vtkIdList;
class vtkIncrementalPointLocator;
class vtkPoints;
class vtkUnstructuredGrid;

namespace fd3vtk
{
class PointInsertion
{
public:
  /// The kernel's mesh of vtkDelaunay3D's octahedron (`center` +- `length` along each axis), its
  /// 6 points at ids count..count+5 of `points` (through `locator` where there is one, which then
  /// also merges the points inserted later), and its tetrahedra as the first cells of `mesh`,
  /// whose links are built.
  PointInsertion(vtkUnstructuredGrid* mesh, vtkPoints* points, const double center[3],
    double length, vtkIdType count, vtkIncrementalPointLocator* locator);

  enum class Outcome
  {
    Inserted,
    Merged,   ///< a repeat of an inserted point (or, with a locator, within its tolerance)
    NotFinite ///< NaN or infinite coordinates: not inserted
  };
  /// Inserts point `id` at x: its coordinates go into `points`; the cells of the tetrahedra it
  /// deletes are given to those it makes, and those left over, which hold stale ids from then on,
  /// are appended to `holeTetras` (as vtkDelaunay3D's InsertPoint does).
  Outcome Insert(vtkUnstructuredGrid* mesh, vtkPoints* points, vtkIdType id, const double x[3],
    vtkIdList* holeTetras);

private:
  /// Writes the kernel's tetrahedron t into `mesh` at a cell of Freed's, or a new one.
  void MakeCell(vtkUnstructuredGrid* mesh, std::uint32_t t);

  fd3::IncrementalDelaunay Kernel;
  vtkIncrementalPointLocator* Locator;
  std::vector<vtkIdType> PointOf; ///< per kernel point id: the caller's point id
  std::vector<vtkIdType> CellOf;  ///< per kernel tetrahedron id: its cell of the mesh, or -1
  std::vector<vtkIdType> Freed;   ///< cells of tetrahedra the insertion under way deleted
  fd3::MeshChange Change;
};
} // namespace fd3vtk

#endif
