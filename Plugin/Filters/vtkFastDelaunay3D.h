/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
/**
 * @class   vtkFastDelaunay3D
 * @brief   exact and fast 3D Delaunay tetrahedralization of the input points
 *
 * vtkFastDelaunay3D is a drop-in alternative to vtkDelaunay3D. It takes any vtkPointSet (and, beyond
 * vtkDelaunay3D, any other vtkDataSet such as image data, whose points it makes explicit) and
 * produces a vtkUnstructuredGrid that holds the input points (same ids, same point data) and
 * VTK_TETRA cells forming the Delaunay tetrahedralization of their convex hull.
 *
 * Unlike vtkDelaunay3D the result is exact: every orientation and in-sphere decision is made with
 * exact arithmetic behind a floating-point filter, and ties (cospherical or coplanar points, such as
 * lattices) are broken consistently by symbolic perturbation. The boundary of the output is exactly
 * the convex hull of the points, and every distinct point is used. Exact duplicates are merged: the
 * copies stay in the output as unused points and their number is reported.
 *
 * The kernel follows "Fast Delaunay triangulation in three dimensions" (Bowyer-Watson insertion, a
 * background grid searched layer by layer, a random walk to the containing tetrahedron, the cavity
 * grown through adjacency and filled without searching), with points inserted in BRIO/Hilbert order.
 *
 * @warning
 * Points with NaN or infinite coordinates are reported with an error and left out of the
 * tetrahedralization (they remain in the output as unused points). Fewer than 4 distinct points,
 * or points that are all collinear or coplanar, give a warning and an output without cells. An
 * empty input gives a warning and an empty output; an aborted run an empty output; an internal
 * failure (such as running out of memory) an error and an empty output.
 *
 * @sa
 * vtkDelaunay3D vtkDelaunay2D
 */
#ifndef vtkFastDelaunay3D_h
#define vtkFastDelaunay3D_h

#include "FastDelaunay3DFiltersModule.h" // For export macro
#include "vtkUnstructuredGridAlgorithm.h"

class FASTDELAUNAY3DFILTERS_EXPORT vtkFastDelaunay3D : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkFastDelaunay3D* New();
  vtkTypeMacro(vtkFastDelaunay3D, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum InsertionOrders
  {
    BRIO_HILBERT = 0,
    INPUT_ORDER = 1,
    RANDOM_ORDER = 2
  };

  ///@{
  /**
   * Resolution of the background grid used to find a starting point for each insertion, as the
   * target number of points per grid cell. 0 turns the grid off (each walk then starts from the
   * last created tetrahedron). Default is 4, chosen by measurement (README).
   */
  vtkSetClampMacro(GridResolution, double, 0.0, 1000.0);
  vtkGetMacro(GridResolution, double);
  ///@}

  ///@{
  /**
   * Sliver guard (the paper's core correction with a volume threshold): no tetrahedron is created
   * whose volume is below this fraction of the volume of the regular tetrahedron on its longest
   * edge, except around the inserted point itself, where no other choice exists. The output is then
   * a valid triangulation of the convex hull but no longer exactly Delaunay. Default 0: exact
   * Delaunay.
   */
  vtkSetClampMacro(VolumeThreshold, double, 0.0, 1.0);
  vtkGetMacro(VolumeThreshold, double);
  ///@}

  ///@{
  /**
   * Order in which points are inserted: BRIO_HILBERT (default, fastest), INPUT_ORDER or
   * RANDOM_ORDER. The output is the same Delaunay tetrahedralization whatever the order, except
   * where ties are broken (cospherical points), which depends on the order.
   */
  vtkSetClampMacro(InsertionOrder, int, BRIO_HILBERT, RANDOM_ORDER);
  vtkGetMacro(InsertionOrder, int);
  ///@}

  ///@{
  /**
   * Seed of the randomized parts (BRIO rounds, the random walk). The same seed gives the same
   * output. Default is 1.
   */
  vtkSetMacro(RandomSeed, int);
  vtkGetMacro(RandomSeed, int);
  ///@}

  ///@{
  /**
   * Figures of the last execution: distinct points inserted, exact duplicates merged, points with
   * NaN/Inf coordinates skipped, tetrahedra produced, mean walk length, and seconds in the kernel.
   */
  vtkGetMacro(NumberOfInsertedPoints, vtkIdType);
  vtkGetMacro(NumberOfDuplicatePoints, vtkIdType);
  vtkGetMacro(NumberOfInvalidPoints, vtkIdType);
  vtkGetMacro(NumberOfTetrahedra, vtkIdType);
  vtkGetMacro(MeanWalkLength, double);
  vtkGetMacro(KernelSeconds, double);
  ///@}

protected:
  vtkFastDelaunay3D();
  ~vtkFastDelaunay3D() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  double GridResolution = 4.0;
  double VolumeThreshold = 0.0;
  int InsertionOrder = BRIO_HILBERT;
  int RandomSeed = 1;

  vtkIdType NumberOfInsertedPoints = 0;
  vtkIdType NumberOfDuplicatePoints = 0;
  vtkIdType NumberOfInvalidPoints = 0;
  vtkIdType NumberOfTetrahedra = 0;
  double MeanWalkLength = 0.0;
  double KernelSeconds = 0.0;

private:
  vtkFastDelaunay3D(const vtkFastDelaunay3D&) = delete;
  void operator=(const vtkFastDelaunay3D&) = delete;
};

#endif
