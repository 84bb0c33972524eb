/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
/**
 * @class   vtkPFastVoronoi3D
 * @brief   vtkFastVoronoi3D across MPI ranks: each rank outputs the cells of the points it owns
 *
 * With more than one process in its controller, the filter computes the Voronoi cells of the
 * points of every rank together, whatever rank holds them. The points are spread over the ranks
 * by space and exchange their halo as in vtkPFastDelaunay3D: afterwards each rank holds, beside
 * its own points, every Delaunay neighbour of them in the whole set, so the cell of each own point
 * among these points is its cell in the whole set. Each rank then outputs the cells of its own
 * distinct finite points, clipped to Bounds (by default the bounding box of all ranks' finite
 * points), with their point data, and GeneratorId, the input id of each cell's point (its
 * position in the input pieces taken in rank order). Together the pieces are the one-process
 * output's cells: the same faces and neighbours, and volumes and vertices equal to rounding (a
 * rank computes a shared vertex from the same points, possibly in another order). Weighted
 * points (Weights) give power cells across ranks, with the halo of vtkPFastDelaunay3D's weighted
 * run; a hidden point's cell is empty on the rank that owns it. The figures (getters, field data)
 * count all ranks. With one process, or a controller that is not MPI, this is vtkFastVoronoi3D.
 *
 * In a periodic box (Periodic), each rank gets the other ranks' points with an image within its
 * halo, widened until every tetrahedron at its points is certain, as vtkPFastDelaunay3D does, and
 * outputs its own points' periodic cells (fd3::voronoiCellsPeriodicPiece). With Weights, the
 * first rank gathers every point and outputs every periodic power cell, as one process does.
 *
 * @warning
 * Coplanar or collinear input has no tetrahedron to find a halo with: every rank then receives
 * all points.
 *
 * @sa
 * vtkFastVoronoi3D vtkPFastDelaunay3D
 */
#ifndef vtkPFastVoronoi3D_h
#define vtkPFastVoronoi3D_h

#include "FastDelaunay3DParallelFiltersModule.h" // For export macro
#include "vtkFastVoronoi3D.h"

#include <string> // for std::string
#include <vector> // for std::vector

namespace fd3
{
template <typename T>
struct BulkAllocator; // the allocator of fd3::Coordinates
struct Bounds;
struct VoronoiCells;
} // namespace fd3

class vtkMultiProcessController;

class FASTDELAUNAY3DPARALLELFILTERS_EXPORT vtkPFastVoronoi3D : public vtkFastVoronoi3D
{
public:
  static vtkPFastVoronoi3D* New();
  vtkTypeMacro(vtkPFastVoronoi3D, vtkFastVoronoi3D);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The ranks that compute the cells together. Default: the global controller.
   */
  virtual void SetController(vtkMultiProcessController*);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /**
   * Points that ranks received from other ranks in the last execution, all ranks together (the
   * cost of the exchange; 0 with one process).
   */
  vtkGetMacro(NumberOfGhostPoints, vtkIdType);

protected:
  vtkPFastVoronoi3D();
  ~vtkPFastVoronoi3D() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  /// The periodic cells, each rank its own points' (fd3vtk::PeriodicRun). Returns as RequestData
  /// does.
  int PeriodicPieceCells(vtkDataSet* input, vtkUnstructuredGrid* output, vtkPolyData* faces);
  /// A rank's output from the cells of its `own` points, the first of `xyz` (then its ghosts,
  /// whose input ids `inputIds` gives after the own points', where GenerateFaces asks for them),
  /// with the figures of every rank. The generators' coordinates come from `xyz`, which is freed
  /// where the polyhedra do not need it. Returns as RequestData does.
  int OutputPieceCells(fd3::VoronoiCells& cells,
    std::vector<double, fd3::BulkAllocator<double>>& xyz, vtkPointData* ownData,
    const std::vector<vtkIdType>& inputIds, std::size_t own, vtkIdType inputPoints, bool weighted,
    const fd3::Bounds& box, vtkUnstructuredGrid* output, vtkPolyData* faces);
  /// Ends an execution that some rank could not finish: aborted, it runs again on the next update;
  /// failed (`failure`: this rank's reason, when it was this rank), the output is empty.
  int Stop(const std::string& failure, bool anyFailed);

  vtkPFastVoronoi3D(const vtkPFastVoronoi3D&) = delete;
  void operator=(const vtkPFastVoronoi3D&) = delete;

  vtkMultiProcessController* Controller = nullptr;
  vtkIdType NumberOfGhostPoints = 0;
};

#endif
