/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "PointInsertion.h"

#include "vtkCellType.h"
#include "vtkIdList.h"
#include "vtkIncrementalPointLocator.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include <array>
#include <cfloat>

namespace
{
/// The octahedron's 6 points, x, y, z each, in vtkDelaunay3D's order: -x, +x, -y, +y, -z, +z.
std::array<double, 18> Octahedron(const double center[3], double length)
{
  std::array<double, 18> xyz;
  for (int k = 0; k < 6; ++k)
  {
    for (int a = 0; a < 3; ++a)
    {
      xyz[3 * k + a] = center[a];
    }
    xyz[3 * k + k / 2] += k % 2 ? length : -length;
  }
  return xyz;
}

/// The kernel's options for one point at a time on the calling thread.
fd3::Options OneThread()
{
  fd3::Options options;
  options.threads = 1;
  options.computeNeighbors = false;
  return options;
}

/// The identity frame over every finite double: the points inserted later are not known, and the
/// identity frame keeps every predicate exact at any magnitude.
fd3::Frame AnyFinitePoint()
{
  const double minMax[6] = { -DBL_MAX, DBL_MAX, -DBL_MAX, DBL_MAX, -DBL_MAX, DBL_MAX };
  return fd3::identityFrame(fd3::Bounds::fromMinMax(minMax));
}
} // namespace

namespace fd3vtk
{
PointInsertion::PointInsertion(vtkUnstructuredGrid* mesh, vtkPoints* points, const double center[3],
  double length, vtkIdType count, vtkIncrementalPointLocator* locator)
  : Kernel(Octahedron(center, length).data(), 6, OneThread(), AnyFinitePoint()), Locator(locator)
{
  const std::array<double, 18> octahedron = Octahedron(center, length);
  if (this->Locator)
  {
    double bounds[6];
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = center[a] - length;
      bounds[2 * a + 1] = center[a] + length;
    }
    this->Locator->InitPointInsertion(points, bounds);
  }
  for (vtkIdType k = 0; k < 6; ++k)
  {
    this->PointOf.push_back(count + k);
    if (this->Locator)
    {
      this->Locator->InsertPoint(count + k, &octahedron[3 * k]);
    }
    else
    {
      points->InsertPoint(count + k, &octahedron[3 * k]);
    }
  }
  mesh->SetPoints(points);
  mesh->Allocate(5 * count + 16);
  mesh->BuildLinks();
  for (const std::uint32_t t : this->Kernel.liveTetrahedra())
  {
    this->MakeCell(mesh, t);
  }
}

PointInsertion::Outcome PointInsertion::Insert(vtkUnstructuredGrid* mesh, vtkPoints* points,
  vtkIdType id, const double x[3], vtkIdList* holeTetras)
{
  if (this->Locator && this->Locator->IsInsertedPoint(x) >= 0)
  {
    return Outcome::Merged;
  }
  const bool inserted = this->Kernel.addOne(x, this->Change);
  this->PointOf.push_back(id); // the kernel gives every point an id, inserted or not
  if (!inserted)
  {
    return fd3::isFinite(x) ? Outcome::Merged : Outcome::NotFinite;
  }
  if (this->Locator)
  {
    this->Locator->InsertPoint(id, x);
  }
  else
  {
    points->InsertPoint(id, x);
  }
  for (const std::uint32_t t : this->Change.deleted)
  {
    const vtkIdType cell = this->CellOf[t];
    this->CellOf[t] = -1;
    vtkIdType size;
    const vtkIdType* ids;
    mesh->GetCellPoints(cell, size, ids);
    for (vtkIdType k = 0; k < size; ++k)
    {
      mesh->RemoveReferenceToCell(ids[k], cell);
    }
    this->Freed.push_back(cell);
  }
  for (const std::uint32_t t : this->Change.made)
  {
    this->MakeCell(mesh, t);
  }
  for (const vtkIdType cell : this->Freed)
  {
    holeTetras->InsertNextId(cell);
  }
  this->Freed.clear();
  return Outcome::Inserted;
}

void PointInsertion::MakeCell(vtkUnstructuredGrid* mesh, std::uint32_t t)
{
  std::uint32_t kernelIds[4];
  this->Kernel.tetrahedron(t, kernelIds);
  vtkIdType ids[4];
  for (int k = 0; k < 4; ++k)
  {
    ids[k] = this->PointOf[kernelIds[k]];
  }
  vtkIdType cell;
  if (!this->Freed.empty())
  {
    cell = this->Freed.back();
    this->Freed.pop_back();
    mesh->ReplaceCell(cell, 4, ids);
    for (const vtkIdType id : ids)
    {
      mesh->ResizeCellList(id, 1);
      mesh->AddReferenceToCell(id, cell);
    }
  }
  else
  {
    cell = mesh->InsertNextLinkedCell(VTK_TETRA, 4, ids);
  }
  if (this->CellOf.size() <= t)
  {
    this->CellOf.resize(t + 1, -1);
  }
  this->CellOf[t] = cell;
}
} // namespace fd3vtk
