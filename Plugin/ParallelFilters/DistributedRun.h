/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
// The distributed Delaunay tetrahedralization that vtkPFastDelaunay3D and vtkPFastVoronoi3D share
// (see vtkPFastDelaunay3D's class documentation): the points spread over the MPI ranks by space,
// one exact frame, each rank's mesh, the halo exchanged once, the ghosts added. A private header
// of the ParallelFilters module.
#ifndef DistributedRun_h
#define DistributedRun_h

#include "PointExchange.h"
#include "RankGroup.h"

#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "fd3/Distributed.h"

#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkDataSet;
class vtkMultiProcessController;
class vtkPointSet;
class vtkPoints;
class vtkPolyData;
class vtkUnstructuredGrid;

namespace fd3vtk
{
/// The point data array of every point's input id (its position in the input pieces taken in rank
/// order).
constexpr const char* kInputIds = "GlobalIds";
/// The point data array that carries weighted points' weights to other ranks: point data travels
/// with its points. It leaves the point data once the ghosts are in.
constexpr const char* kWeights = "FastDelaunay3DWeights";

using fd3::Coordinates;

/// One status for every rank's run (a collective call): a failed check, or points too far apart
/// for doubles, on any rank; else Ok where any rank has tetrahedra; else the most telling of
/// Degenerate, TooFewPoints and Empty. A status outside these (an abort) counts as a failed check.
fd3::Status StatusOfAllRanks(vtkMultiProcessController* controller, fd3::Status mine);

/// The figures of every rank's run summed, with each thing counted by the rank that owns it: the
/// counts summed, the times and longest walk the largest.
void SumFigures(vtkMultiProcessController* controller, fd3::Statistics& stats);

/// Weighted points, as one rank read them from its input piece before the run.
struct InputWeights
{
  bool Found = false;         ///< whether the piece has the weights array
  std::vector<double> Values; ///< one per input point, radii squared where they are radii
  std::string Problem;        ///< why they could not be read, which stops every rank
};

/// The weights of a piece's `points` points from the filter's weights `array` (null where the
/// piece has none): as fd3vtk::PointWeights() reads them.
InputWeights ReadInputWeights(vtkDataArray* array, vtkIdType points, bool radii);

/// This rank's points once spread by space: the finite points in its part of space, then its own
/// non-finite ones (nothing to triangulate, but they stay in the output as unused points).
struct OwnPoints
{
  Coordinates Xyz; ///< 3 per point; the mesh takes them and gives them back
  vtkSmartPointer<vtkPointData> Data;
  std::size_t Count = 0;
  std::size_t Finite = 0; ///< the first points, the finite ones
};

/// One execution across the ranks, step by step (see the class documentation). Each step returns
/// whether every rank got through it (RankGroup); a step that returns false stopped them all.
class DistributedRun
{
public:
  /// A run over the ranks of `controller`, each on `threads` threads.
  DistributedRun(vtkMultiProcessController* controller, int threads);

  /// Step 1: the finite points spread over the ranks by space (PointExchange::BalancedCuts()),
  /// with their point data and input ids, this rank's non-finite ones after them. `points`: the
  /// input's, in the output's precision. The run is weighted where any rank found `weights`; each
  /// point's weight then travels with it (kWeights), and a piece with points but no weights, or
  /// a Problem on any rank, stops every rank. `cutBy`, where given, places each point for the
  /// cuts instead of its coordinates (a periodic point's place in the box), NaN where not finite.
  bool Redistribute(vtkDataSet* input, vtkPoints* points, const InputWeights& weights = {},
    vtkDataArray* cutBy = nullptr);

  /// Step 2: one exact frame for every rank, from the global bounds (computed here once, for the
  /// diagonal too) and the shifts that are exact on every rank. `later`, where given, makes from
  /// the global bounds the points (x, y, z each, the same on every rank) that every rank adds to
  /// its mesh after the ghosts: the frame holds them too. Weighted: the frame holds every weight
  /// too, and Heaviest is found.
  bool ChooseFrame(const std::function<std::vector<double>(const fd3::Bounds&)>& later = nullptr);

  /// Step 3: this rank's points tetrahedralized. The mesh takes them, and frees them where its
  /// records give them back, so that they are not in the rank's peak.
  bool Triangulate(const fd3::Options& options);

  /// Step 4: the halo of every other rank sent to it (fd3::haloVertices).
  bool ExchangeHalo();

  /// Step 5: the received points (and their weights) added to this rank's mesh, the output taken
  /// from it with every point's coordinates, and the owner of every point.
  bool AddGhosts();
  /// Step 5 for a caller that ends the mesh itself: the received points added, then `finish`
  /// given the mesh and Xyz, where it must release the mesh's coordinates (it returns false when
  /// aborted); Result stays empty.
  bool AddGhosts(const std::function<bool(fd3::IncrementalDelaunay&, Coordinates&)>& finish);

  /// Step 6: the figures and status of all ranks together.
  fd3::Statistics GlobalFigures(fd3::Status& status);

  /// Whether this rank owns the simplex: it owns its lexicographically smallest vertex, which
  /// every rank holding the simplex finds alike. A vertex cell (a point on no other cell of the
  /// alpha shape, or a duplicate) goes with the point itself. Every position is one rank's
  /// alone: the cuts send a point by its coordinates, so the copies of a position go to one rank
  /// (which merges them) and no ghost repeats an own point.
  bool Owns(const std::uint32_t* ids, int size) const;

  /// Step 7, after the cells: the output's points, this rank's own, then the received ones its
  /// cells use (as duplicate points, in the order received), with the cells' ids renumbered to
  /// match, and their point data.
  void SetOutputPoints(vtkUnstructuredGrid* output);

  /// This rank's own points, the first of Xyz: the finite ones in its part of space, then its
  /// non-finite ones.
  std::size_t OwnCount() const { return this->Own.Count; }
  /// The finite ones of them, the first.
  std::size_t OwnFinite() const { return this->Own.Finite; }
  /// Until step 3 takes them: the own points' coordinates, 3 each.
  const Coordinates& OwnXyz() const { return this->Own.Xyz; }
  /// From step 1: the type of the output's points, as one process's output would have them.
  int OutputPointType() const { return this->PointType; }
  /// The own points `halo`, at `xyz` (3 each), with their point data: a part to send.
  vtkSmartPointer<vtkPolyData> HaloPart(
    const std::vector<std::uint32_t>& halo, const std::vector<double>& xyz) const;
  /// The point data of the own points, with every point's input id (kInputIds).
  vtkPointData* OwnData() const { return this->Own.Data; }
  /// From step 5: the input id of each point of Xyz, the own points' and the received ones'.
  std::vector<vtkIdType> InputIds() const;
  /// Weighted: the weight of each point so far (the own points', then from step 5 the received
  /// ones'), never null, even with no point; else null.
  const double* WeightsOrNull() const;

  RankGroup Ranks;
  const int Threads;
  fd3::Bounds GlobalBounds;  ///< from step 2: of every rank's finite points
  vtkIdType InputPoints = 0; ///< all ranks'
  vtkIdType GhostPoints = 0; ///< all ranks'
  double Diagonal = 0;       ///< of the global bounds
  fd3::Triangulation Result; ///< this rank's: its points and the received ones
  Coordinates Xyz;           ///< from step 5: this rank's points, then the received ones
  bool Weighted = false;     ///< from step 1: whether any rank's points are weighted
  double Heaviest = 0;       ///< from step 2, weighted: the largest finite weight of all ranks

private:
  /// The ghost points that room is made for up front, in Xyz and in the mesh's vertex records: a
  /// rank receives a few percent of its own count at 1M points a rank, more on small ones.
  /// Growing either later would copy it, and under MPI the copy's source stays resident (Open MPI
  /// keeps the freed pages).
  static std::size_t GhostRoom(std::size_t own) { return own / 4 + 1024; }

  /// The finite points `finite` sent to the ranks whose part of space holds them; `parts`: those
  /// this rank gets, its own among them, in rank order.
  bool SpreadFinite(vtkDataArray* coordinates, vtkDataArray* cutBy, vtkPointData* data,
    std::vector<vtkIdType>& finite, Received& parts);

  /// The weights array (kWeights) that `parts` carry, appended to Weights, and taken out of
  /// their point data where `remove`.
  void TakeWeights(const std::vector<vtkPointData*>& parts, bool remove);

  /// OwnPoints from the parts received and this rank's non-finite points, with room for the
  /// ghosts in Xyz.
  void Gather(vtkDataArray* coordinates, vtkPointData* data,
    const std::vector<vtkIdType>& nonFinite, Received& parts);

  std::vector<fd3::Bounds> OtherBoxes() const;

  /// Every finite point for every other rank: without a tetrahedron to choose from, any point
  /// might matter.
  std::vector<std::vector<std::uint32_t>> AllToAll() const;

  /// The counts of what this rank owns, in place of its mesh's: its vertices, the points merged
  /// into them or skipped, and the tetrahedra.
  void CountOwned(fd3::Statistics& stats) const;

  /// The point data of the output's points: this rank's own, then that of the received points
  /// in use (ghostId >= 0), with GlobalIds and the ghost marks.
  void SetOutputPointData(vtkUnstructuredGrid* output, const std::vector<vtkIdType>& ghostId);

  PointExchange Exchange;
  int PointType = VTK_DOUBLE; ///< of the output's points
  OwnPoints Own;
  std::vector<fd3::Bounds> Boxes; ///< every rank's bounds
  fd3::Frame Frame;
  std::unique_ptr<fd3::IncrementalDelaunay> Mesh;
  double MeshSeconds = 0;
  Received Ghosts;
  std::vector<int> Owner;      ///< per point of Xyz: the rank whose own point it is
  std::vector<double> Weights; ///< weighted: per point of Xyz
};
} // namespace fd3vtk

#endif
