#include "VtkTestUtilities.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

namespace fd3test
{

vtkSmartPointer<vtkPolyData> toPolyData(const Points& p, int type)
{
  vtkNew<vtkPoints> points;
  points->SetDataType(type);
  const vtkIdType n = static_cast<vtkIdType>(p.size() / 3);
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i)
    points->SetPoint(i, p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  return cloud;
}

std::vector<std::uint32_t> tetrahedra(vtkUnstructuredGrid* grid)
{
  std::vector<std::uint32_t> tets;
  vtkIdType size;
  const vtkIdType* ids;
  auto it = vtk::TakeSmartPointer(grid->GetCells()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    it->GetCurrentCell(size, ids);
    if (size != 4)
      return {};
    tets.insert(tets.end(), ids, ids + size);
  }
  return tets;
}

Points coordinates(vtkPointSet* data)
{
  Points p(3 * static_cast<std::size_t>(data->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
    data->GetPoint(i, p.data() + 3 * i);
  return p;
}

ValidityReport checkOutput(vtkUnstructuredGrid* grid, const ValidityOptions& options)
{
  const Points xyz = coordinates(grid);
  return checkTriangulation(xyz.data(), xyz.size() / 3, tetrahedra(grid), options);
}

double sum(vtkDataArray* array)
{
  double total = 0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
    total += array->GetTuple1(i);
  return total;
}

} // namespace fd3test
