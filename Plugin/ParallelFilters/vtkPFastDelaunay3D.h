/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
/**
 * @class   vtkPFastDelaunay3D
 * @brief   vtkFastDelaunay3D across MPI ranks: one Delaunay tetrahedralization of all their points
 *
 * With more than one process in its controller, the filter tetrahedralizes the points of every
 * rank together, whatever rank holds them:
 * 1. the finite points are spread over the ranks by space, balanced by count (a k-d split of a
 *    sample of all ranks' points, sent as arrays through DIY), each with its point data and
 *    its input id (position in the input pieces taken in rank order) in a "GlobalIds" array;
 * 2. every rank computes in one exact frame made from the global bounds, so that every rank
 *    decides every predicate, and every tie, alike;
 * 3. each rank tetrahedralizes its points and sends every other rank the vertices of its
 *    tetrahedra whose circumsphere meets that rank's bounds (fd3::haloVertices), sent the same
 *    way; one exchange is enough (Funke and Sanders, 2017); the mesh takes the rank's points,
 *    and frees them where its records give them back exactly, so that they are not in the
 *    rank's peak;
 * 4. each rank adds the points it received and keeps the tetrahedra whose lexicographically
 *    smallest vertex it owns (every position is one rank's: the cuts send a point by its
 *    coordinates, so the copies of a position all go to one rank, which merges them).
 *
 * Weighted points (Weights) give the regular tetrahedralization across ranks too: each point's
 * weight travels with it, and step 3 sends the vertices of the tetrahedra whose orthogonal sphere,
 * widened to the power distance of the heaviest point of all ranks, meets a rank's bounds, so a
 * heavy point far from a rank reaches it where it matters. Each rank hides its own hidden points
 * as one process hides them; NumberOfHiddenPoints counts all ranks'.
 *
 * Each rank's output then holds the tetrahedra it owns (or, with Alpha, the alpha shape's cells it
 * owns), its own points with their point data, and the other ranks' points that those cells use,
 * marked as duplicate points in vtkGhostType; "GlobalIds" gives every output point its input id.
 * Together the pieces are exactly the one-process output's cells. The figures (getters, field
 * data) count all ranks. With one process, or a controller that is not MPI, this is
 * vtkFastDelaunay3D.
 *
 * A periodic box (Periodic) is spread by the points' places in the box, wrapped into it. Each
 * rank receives every other rank's points with an image within a halo of its region (the bounds
 * of its places), a few spacings wide at first, and triangulates its points among their images
 * and those points' (fd3::triangulatePeriodicPiece). Where a tetrahedron at one of its points
 * might reach beyond the halo, the rank asks for a wider one, which the other ranks fill, and
 * runs again (a cluster in an empty box, a slab's caps). Each rank then outputs
 * the periodic tetrahedra whose least vertex (least input id, then offset 0) is one of its
 * points: its points first, then the image points its tetrahedra use (another rank's point, or
 * a point a period away), each with its input point's point data and "SourcePointId", its input
 * id. Density comes from each point's whole star; an image takes its input point's, sent back by
 * the rank that owns it. With Alpha, each rank takes the stars of its points (every periodic
 * tetrahedron at them), whose alpha shape holds every simplex at them as the whole set's does,
 * and keeps the simplices whose least vertex is one of its points. Together the pieces are the
 * one-process output's cells, each once. With Weights, the first rank gathers every rank's
 * points and outputs the periodic regular tetrahedralization, as one process does.
 *
 * @warning
 * Output point ids are not input point ids under MPI: the points move between ranks; GlobalIds
 * maps them back. BoundingTriangulation is not available across ranks (the output is empty, with
 * an error). Tolerance, when above 0, is applied by each rank to its own points.
 *
 * @sa
 * vtkFastDelaunay3D vtkDIYUtilities
 */
#ifndef vtkPFastDelaunay3D_h
#define vtkPFastDelaunay3D_h

#include "FastDelaunay3DParallelFiltersModule.h" // For export macro
#include "vtkFastDelaunay3D.h"

#include <string> // for std::string

class vtkMultiProcessController;

class FASTDELAUNAY3DPARALLELFILTERS_EXPORT vtkPFastDelaunay3D : public vtkFastDelaunay3D
{
public:
  static vtkPFastDelaunay3D* New();
  vtkTypeMacro(vtkPFastDelaunay3D, vtkFastDelaunay3D);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The ranks that triangulate together. Default: the global controller.
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
  vtkPFastDelaunay3D();
  ~vtkPFastDelaunay3D() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  /// The periodic tetrahedralization, each rank's piece (fd3vtk::PeriodicRun): its tetrahedra
  /// whose least vertex it owns, its points and the image points those use. Returns as
  /// RequestData does.
  int TriangulatePeriodicPieces(vtkDataSet* input, vtkUnstructuredGrid* output);
  /// Ends an execution that some rank could not finish: aborted, it runs again on the next update;
  /// failed (`failure`: this rank's reason, when it was this rank), the output keeps the points.
  int Stop(const std::string& failure, bool anyFailed, vtkUnstructuredGrid* output,
    vtkPoints* inputPoints, vtkPointData* inputData);

  vtkPFastDelaunay3D(const vtkPFastDelaunay3D&) = delete;
  void operator=(const vtkPFastDelaunay3D&) = delete;

  vtkMultiProcessController* Controller = nullptr;
  vtkIdType NumberOfGhostPoints = 0;
};

#endif
