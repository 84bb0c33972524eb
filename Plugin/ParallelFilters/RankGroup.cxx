/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "RankGroup.h"

#include "vtkCommunicator.h"
#include "vtkMPIController.h"
#include "vtkMultiProcessController.h"

namespace fd3vtk
{
bool IsDistributed(vtkMultiProcessController* controller)
{
  return vtkMPIController::SafeDownCast(controller) && controller->GetNumberOfProcesses() > 1;
}

bool AnyRank(vtkMultiProcessController* controller, bool mine)
{
  const int local = mine;
  int any = 0;
  controller->AllReduce(&local, &any, 1, vtkCommunicator::MAX_OP);
  return any != 0;
}

RankGroup::RankGroup(vtkMultiProcessController* controller)
  : Controller(controller), Rank(controller->GetLocalProcessId()),
    Size(controller->GetNumberOfProcesses())
{}

bool RankGroup::AllSucceeded(bool succeeded)
{
  int local[2] = { succeeded, this->Failure.empty() }, global[2] = { 0, 0 };
  this->Controller->AllReduce(local, global, 2, vtkCommunicator::MIN_OP);
  this->AnyFailed = global[1] == 0;
  return global[0] != 0;
}
} // namespace fd3vtk
