/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "GatheredPoints.h"

#include "FilterInput.h"

#include "vtkAlgorithm.h"
#include "vtkAppendFilter.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <vector>

namespace fd3vtk
{

vtkSmartPointer<vtkPointSet> GatheredPoints(vtkMultiProcessController* controller,
  vtkDataSet* input, vtkAlgorithm* filter, const char* noPoints)
{
  // Points and point data only: the cells are not wanted, and are no cost to send.
  vtkNew<vtkPolyData> piece;
  vtkNew<vtkPoints> none;
  piece->SetPoints(none);
  if (input && input->GetNumberOfPoints() > 0)
  {
    piece->SetPoints(PointsInPrecision(input, vtkAlgorithm::DEFAULT_PRECISION));
    piece->GetPointData()->ShallowCopy(input->GetPointData());
  }
  std::vector<vtkSmartPointer<vtkDataObject>> pieces;
  controller->Gather(piece, pieces, 0);
  if (controller->GetLocalProcessId() != 0)
  {
    return nullptr;
  }
  vtkNew<vtkAppendFilter> append; // keeps every point, in order, with the arrays all pieces have
  append->MergePointsOff();
  for (const auto& received : pieces)
  {
    append->AddInputData(received);
  }
  append->Update();
  vtkSmartPointer<vtkPointSet> all = append->GetOutput();
  if (all->GetNumberOfPoints() == 0)
  {
    vtkWarningWithObjectMacro(filter, << noPoints);
    return nullptr;
  }
  return all;
}

} // namespace fd3vtk
