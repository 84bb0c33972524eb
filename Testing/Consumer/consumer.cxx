#include "vtkFastDelaunay3D.h"
#include "vtkNew.h"
#include "vtkPointSource.h"
#include "vtkUnstructuredGrid.h"

#include <iostream>

int main()
{
  vtkNew<vtkPointSource> points;
  points->SetNumberOfPoints(1000);
  vtkNew<vtkFastDelaunay3D> delaunay;
  delaunay->SetInputConnection(points->GetOutputPort());
  delaunay->Update();
  std::cout << delaunay->GetOutput()->GetNumberOfCells() << " tetrahedra\n";
  return delaunay->GetOutput()->GetNumberOfCells() > 0 ? 0 : 1;
}
