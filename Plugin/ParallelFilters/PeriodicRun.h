/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// The periodic tetrahedralization and cells across MPI ranks that vtkPFastDelaunay3D and
// vtkPFastVoronoi3D share: the points spread over the ranks by their places in the box, each
// rank's ghosts (every other rank's points with an image within its halo), and the kernel's run
// of the rank's piece (fd3::PeriodicPiece), again after a wider exchange for as long as some rank
// asks for one. A private header of the ParallelFilters module.
#ifndef PeriodicRun_h
#define PeriodicRun_h

#include "DistributedRun.h"
#include "PointExchange.h"

#include "vtkSmartPointer.h"

#include "fd3/Periodic.h"

#include <cstdint>
#include <functional>
#include <vector>

class vtkDataSet;
class vtkMultiProcessController;
class vtkPointData;
class vtkPoints;

namespace fd3vtk
{
/// The bounds of the finite ones of `points` (null: none) of every rank: a collective call.
fd3::Bounds GlobalFiniteBounds(vtkMultiProcessController* controller, vtkPoints* points);

/// One periodic execution across the ranks, step by step; each step returns whether every rank
/// got through it (RankGroup), as DistributedRun's.
class PeriodicRun
{
public:
  /// The run of `run`'s ranks in `box`, which every rank gives alike.
  PeriodicRun(DistributedRun& run, const fd3::PeriodicBox& box);

  /// Step 1: run.Redistribute() by the points' places in the box, which the cuts then split (a
  /// point outside the box goes where its wrap puts it). A point too far from the box for its
  /// wrap stops every rank.
  bool Redistribute(vtkDataSet* input, vtkPoints* points);

  /// Step 2: every rank's region (the bounds of its points' places), the ghosts within the first
  /// halo, and `piece` run on Xyz; then, on the ranks whose piece asks for a wider halo, the
  /// ghosts within it and `piece` again, until none asks. `piece` sets the halo it asks for (0:
  /// none) and returns false when aborted.
  bool Run(const std::function<bool(const fd3::PeriodicPiece&, double& widerHalo)>& piece);

  /// After step 2: for each ghost, the value that its own rank has in `own` (one per own point).
  bool GhostValues(const std::vector<double>& own, std::vector<double>& ghosts);

  /// The point data of the points of Xyz: the own points', then the ghosts'.
  vtkSmartPointer<vtkPointData> PointData() const;

  /// The own points (run.OwnXyz()), then from step 2 the ghosts.
  Coordinates Xyz;
  /// The input id of each point of Xyz.
  std::vector<std::uint32_t> Ids;
  vtkIdType GhostPoints = 0; ///< all ranks', in the halos their pieces stood in
  int Exchanges = 0;         ///< of ghosts

private:
  /// Sends each other rank r that `to` names the own points with an image within halos[r] of its
  /// region; the ranks named take what they receive as their ghosts, the others keep theirs.
  bool ExchangeGhosts(const std::vector<double>& halos, const std::vector<char>& to);

  DistributedRun& Distributed;
  const fd3::PeriodicBox Box;
  PointExchange Exchange;
  std::vector<double> Places;       ///< of the own points, 3 each (NaN where not finite)
  std::vector<fd3::Bounds> Regions; ///< of every rank
  Received Ghosts;                  ///< of the halo this rank's piece stood in
  std::vector<std::vector<std::uint32_t>> Sent; ///< the own points each rank holds as ghosts
};
} // namespace fd3vtk

#endif
