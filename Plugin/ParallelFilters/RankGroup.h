/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// The ranks of a distributed run and the one error protocol of its collective steps. A private
// header of the ParallelFilters module.
#ifndef RankGroup_h
#define RankGroup_h

#include <exception>
#include <string>

class vtkMultiProcessController;

namespace fd3vtk
{
/// Whether `controller` runs MPI with two processes or more, where the filters run distributed
/// (else they run as their one-process superclasses).
bool IsDistributed(vtkMultiProcessController* controller);

/// Whether `mine` holds on any rank: a collective call.
bool AnyRank(vtkMultiProcessController* controller, bool mine);

/// The ranks of a run and its one error protocol. The local work of each step runs in Local(),
/// which catches what it throws; then every rank learns whether all got through, before any
/// further collective call. A rank that fails (out of memory) or is aborted thus never leaves the
/// others waiting in a collective call: all of them stop after the same step.
class RankGroup
{
public:
  explicit RankGroup(vtkMultiProcessController* controller);

  /// Runs `work` on this rank (it returns false when aborted); whether it succeeded on all.
  template <typename Work>
  bool Local(Work&& work)
  {
    bool succeeded = false;
    try
    {
      succeeded = work();
    }
    catch (const std::exception& error)
    {
      this->Failure = error.what();
    }
    return this->AllSucceeded(succeeded);
  }

  /// Whether every rank succeeded; AnyFailed says whether a rank failed rather than aborted.
  bool AllSucceeded(bool succeeded);

  vtkMultiProcessController* const Controller;
  const int Rank;
  const int Size;
  std::string Failure;    ///< why this rank failed, when it did
  bool AnyFailed = false; ///< whether some rank failed (else a stop was an abort)
};
} // namespace fd3vtk

#endif
