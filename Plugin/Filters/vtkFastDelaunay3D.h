/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
/**
 * @class   vtkFastDelaunay3D
 * @brief   exact and fast 3D Delaunay tetrahedralization of the input points
 *
 * vtkFastDelaunay3D is a drop-in alternative to vtkDelaunay3D, with the same properties, defaults
 * and output. It takes any vtkPointSet (and, beyond vtkDelaunay3D, any other vtkDataSet such as
 * image data, whose points it makes explicit) and produces a vtkUnstructuredGrid holding the input
 * points (same ids, same point data) and VTK_TETRA cells filling their convex hull; with a non-zero
 * Alpha, the alpha shape instead (tetrahedra, then triangles, lines and vertices per the Alpha*
 * flags, as vtkDelaunay3D emits them).
 *
 * Unlike vtkDelaunay3D the result is exact: every orientation and in-sphere decision is made with
 * exact arithmetic behind a floating-point filter, and ties (cospherical or coplanar points, such
 * as lattices) are broken consistently by symbolic perturbation. The boundary of the output is
 * exactly the convex hull of the points, and every distinct point is a vertex. Exact duplicates are
 * merged: the copies stay in the output as unused points. Whatever is left out of the
 * tetrahedralization (duplicates, points within a non-zero Tolerance, NaN/Inf points) is counted,
 * reported in one warning, and recorded in the getters and the field data.
 *
 * The kernel follows "Fast Delaunay triangulation in three dimensions" (Bowyer-Watson insertion, a
 * background grid searched layer by layer, a walk to a tetrahedron in conflict with the point, the
 * cavity grown through adjacency and filled without searching), with points inserted in
 * BRIO/Hilbert order.
 *
 * @warning
 * Points with NaN or infinite coordinates are left out of the tetrahedralization and counted in
 * the warning (they remain in the output as unused points). Fewer than 4 distinct points, or
 * points that are all collinear or coplanar, give a warning and the points with no cells. An
 * empty input gives a warning and an output without points; an aborted run an empty output; an
 * internal failure (such as running out of memory) an error and the points with no cells.
 *
 * @sa
 * vtkDelaunay3D vtkDelaunay2D
 */
#ifndef vtkFastDelaunay3D_h
#define vtkFastDelaunay3D_h

#include "FastDelaunay3DFiltersModule.h" // For export macro
#include "vtkIncrementalPointLocator.h"  // for the Locator's getter
#include "vtkSmartPointer.h"             // for vtkSmartPointer
#include "vtkUnstructuredGridAlgorithm.h"

#include <cstddef>    // for std::size_t
#include <cstdint>    // for std::uint32_t
#include <functional> // for std::function
#include <memory>     // for std::unique_ptr
#include <vector>     // for std::vector

class vtkFieldData;
class vtkIdList;
class vtkPointData;
class vtkPoints;
namespace fd3vtk
{
class PointInsertion;
}
namespace fd3
{
struct AlphaComplex;
struct Bounds;
struct Options;
struct PeriodicPlacement;
struct PeriodicTriangulation;
struct Statistics;
struct Triangulation;
enum class Status;
} // namespace fd3

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
   * Specify alpha (or distance) value to control output of this filter. For a non-zero alpha
   * value, only tetrahedra, triangles, edges and vertices whose circumsphere radius (half-length
   * for edges) is at most alpha are output, and lower-dimensional simplices only where no output
   * simplex already covers them. In other words, an alpha shape is computed. Default 0: the whole
   * tetrahedralization. Clamped to [0, VTK_DOUBLE_MAX]; NaN sets the default.
   */
  virtual void SetAlpha(double alpha);
  vtkGetMacro(Alpha, double);
  virtual double GetAlphaMinValue() { return 0.0; }
  virtual double GetAlphaMaxValue() { return VTK_DOUBLE_MAX; }
  ///@}

  ///@{
  /**
   * Whether tetrahedra, triangles, lines and vertices are output for non-zero alpha values.
   * All on by default (as in vtkDelaunay3D; ParaView's proxy turns lines and vertices off).
   */
  vtkSetMacro(AlphaTets, vtkTypeBool);
  vtkGetMacro(AlphaTets, vtkTypeBool);
  vtkBooleanMacro(AlphaTets, vtkTypeBool);
  vtkSetMacro(AlphaTris, vtkTypeBool);
  vtkGetMacro(AlphaTris, vtkTypeBool);
  vtkBooleanMacro(AlphaTris, vtkTypeBool);
  vtkSetMacro(AlphaLines, vtkTypeBool);
  vtkGetMacro(AlphaLines, vtkTypeBool);
  vtkBooleanMacro(AlphaLines, vtkTypeBool);
  vtkSetMacro(AlphaVerts, vtkTypeBool);
  vtkGetMacro(AlphaVerts, vtkTypeBool);
  vtkBooleanMacro(AlphaVerts, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Discard closely spaced points: a point closer than Tolerance times the diagonal of the
   * bounding box to an inserted point is skipped and stays in the output as an unused point.
   * Default 0: only exact duplicates are merged and every distinct point is a vertex. This default
   * differs from vtkDelaunay3D's 0.001 on purpose: vtkDelaunay3D (VTK 9.2) documents that value but
   * never applies it, so it keeps every point, while applying it here would drop a large part of
   * dense clouds (half of an airborne LiDAR tile). Clamped to [0, 1]; NaN sets the default.
   */
  virtual void SetTolerance(double tolerance);
  vtkGetMacro(Tolerance, double);
  virtual double GetToleranceMinValue() { return 0.0; }
  virtual double GetToleranceMaxValue() { return 1.0; }
  ///@}

  ///@{
  /**
   * Size of the bounding octahedron of BoundingTriangulation, as a multiple of the diagonal of the
   * bounding box of the points. Default 2.5. Clamped to [2.5, VTK_DOUBLE_MAX]; NaN sets the
   * default. The octahedron's points always stay finite: where Offset times the diagonal would
   * take them beyond the largest double, the octahedron is as large as the doubles allow.
   */
  virtual void SetOffset(double offset);
  vtkGetMacro(Offset, double);
  virtual double GetOffsetMinValue() { return 2.5; }
  virtual double GetOffsetMaxValue() { return VTK_DOUBLE_MAX; }
  ///@}

  ///@{
  /**
   * When on, the output also holds the 6 points of a bounding octahedron (appended after the
   * input points) and the tetrahedra that use them, as vtkDelaunay3D does; point data is then not
   * passed. Off by default.
   */
  vtkSetMacro(BoundingTriangulation, vtkTypeBool);
  vtkGetMacro(BoundingTriangulation, vtkTypeBool);
  vtkBooleanMacro(BoundingTriangulation, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Precision of the output points: vtkAlgorithm::DEFAULT_PRECISION (that of the input),
   * SINGLE_PRECISION or DOUBLE_PRECISION; any other value gives single precision, as in
   * vtkDelaunay3D. The tetrahedralization is exact for the output points.
   */
  vtkSetMacro(OutputPointsPrecision, int);
  vtkGetMacro(OutputPointsPrecision, int);
  ///@}

  ///@{
  /**
   * Resolution of the background grid used to find a starting point for each insertion, as the
   * target number of points per grid cell. 0 turns the grid off (each walk then starts from the
   * last created tetrahedron). Default is 4, chosen by measurement (docs/performance.md). Clamped
   * to [0, 1000]; NaN sets the default. Below 1/8, the grid has its most cells: 8 per point.
   */
  virtual void SetGridResolution(double pointsPerCell);
  vtkGetMacro(GridResolution, double);
  ///@}

  ///@{
  /**
   * Sliver guard (the paper's core correction with a volume threshold): no tetrahedron is created
   * whose volume is below this fraction of the volume of the regular tetrahedron on its longest
   * edge, except around the inserted point itself, where no other choice exists. The output is then
   * a valid triangulation of the convex hull but no longer exactly Delaunay. Default 0: exact
   * Delaunay. Clamped to [0, 1]; NaN sets the default.
   */
  virtual void SetVolumeThreshold(double threshold);
  vtkGetMacro(VolumeThreshold, double);
  ///@}

  ///@{
  /**
   * Order in which points are inserted: BRIO_HILBERT (default, fastest), INPUT_ORDER or
   * RANDOM_ORDER. The output is the same Delaunay tetrahedralization whatever the order, except
   * where ties are broken (cospherical points) and which of two points closer than Tolerance is
   * kept.
   */
  vtkSetClampMacro(InsertionOrder, int, BRIO_HILBERT, RANDOM_ORDER);
  vtkGetMacro(InsertionOrder, int);
  ///@}

  ///@{
  /**
   * Seed of the randomized parts: the BRIO rounds, the order in which ties between cospherical
   * points are broken, and the walk's random choice of face where it runs long. The same seed
   * gives the same output. Default is 1.
   */
  vtkSetMacro(RandomSeed, int);
  vtkGetMacro(RandomSeed, int);
  ///@}

  ///@{
  /**
   * Number of threads that insert points. 0 (the default) takes what
   * vtkSMPTools::GetEstimatedNumberOfThreads() reports, so that ParaView's thread setting (or the
   * VTK_SMP_BACKEND_IN_USE and VTK_SMP_MAX_THREADS environment variables) governs it. The output
   * is the same whatever the number of threads. A VolumeThreshold above 0 runs on one thread.
   * At most 4 threads per hardware thread are started (more cannot help, and each costs memory):
   * larger values run as that many.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Optional cell arrays, off by default: "Circumradius" (of tetrahedra and triangles; half the
   * length of lines), "Volume" (of tetrahedra; 0 for other cells) and "RadiusEdgeRatio"
   * (circumradius over shortest edge of tetrahedra, 0.612 for a regular one; 0 for other cells).
   */
  vtkSetMacro(ComputeCircumradius, vtkTypeBool);
  vtkGetMacro(ComputeCircumradius, vtkTypeBool);
  vtkBooleanMacro(ComputeCircumradius, vtkTypeBool);
  vtkSetMacro(ComputeVolume, vtkTypeBool);
  vtkGetMacro(ComputeVolume, vtkTypeBool);
  vtkBooleanMacro(ComputeVolume, vtkTypeBool);
  vtkSetMacro(ComputeRadiusEdgeRatio, vtkTypeBool);
  vtkGetMacro(ComputeRadiusEdgeRatio, vtkTypeBool);
  vtkBooleanMacro(ComputeRadiusEdgeRatio, vtkTypeBool);
  ///@}

  ///@{
  /**
   * When on, a point array "Density": the Delaunay tessellation field estimate, 4 times the input
   * points at each vertex (it and its merged duplicates) over the volume of the tetrahedra around
   * it, whose linear field integrates over the hull to the number of points; on the whole
   * tetrahedralization, with an Alpha too. Hull points have part of a star, so their values run
   * high. NaN for points on no tetrahedron. Off by default.
   */
  vtkSetMacro(ComputeDensity, vtkTypeBool);
  vtkGetMacro(ComputeDensity, vtkTypeBool);
  vtkBooleanMacro(ComputeDensity, vtkTypeBool);
  ///@}

  ///@{
  /**
   * When on, the output's field data holds the figures of the run (see the getters below) as
   * one-tuple arrays named after them. Off by default.
   */
  vtkSetMacro(ComputeStatistics, vtkTypeBool);
  vtkGetMacro(ComputeStatistics, vtkTypeBool);
  vtkBooleanMacro(ComputeStatistics, vtkTypeBool);
  ///@}

  ///@{
  /**
   * A spatial locator that merges close points as vtkDelaunay3D's does: a finite point within the
   * locator's own tolerance (vtkLocator::SetTolerance, a distance; 0.001 for
   * CreateDefaultLocator()'s) of a point before it in input order is merged into that point, left
   * out of the tetrahedralization and counted with the skipped points. None by default: then the
   * kernel's own background grid merges exact duplicates, and Tolerance applies. Tolerance applies
   * with a locator too. A locator is not used across MPI ranks.
   */
  void SetLocator(vtkIncrementalPointLocator* locator);
  vtkGetObjectMacro(Locator, vtkIncrementalPointLocator);
  ///@}

  /**
   * Sets a vtkPointLocator of 25 x 25 x 25 buckets as the locator, where there is none (as
   * vtkDelaunay3D's does).
   */
  void CreateDefaultLocator();

  /**
   * vtkDelaunay3D's incremental API, on the exact kernel. InitPointInsertion returns a new mesh
   * (the caller deletes it) holding a bounding octahedron, `center` +- `length` along each axis
   * (1 where length is not above 0), as points numPts..numPts+5 of `points`, and its tetrahedra;
   * the mesh takes `points` over (the caller's reference: do not delete it). Each InsertPoint then
   * inserts point `id` (below numPts) at x: its coordinates go into `points`, and the mesh is kept
   * the exact Delaunay tetrahedralization of the octahedron and the points inserted. The cells of
   * the tetrahedra a point deletes are given to those it makes; those left over hold stale ids and
   * are appended to `holeTetras` (skip them, and the cells that use the octahedron's points,
   * unless they are wanted). Any finite point can be inserted, inside the octahedron or not; a
   * repeat of an inserted point (or one within the Locator's tolerance, where one is set) and a
   * NaN or infinite point change nothing and are counted as duplicates and invalid points.
   * EndPointInsertion ends the insertion (the caller still deletes the mesh). With numPts 0 the
   * mesh is empty and `points` stays the caller's.
   */
  vtkUnstructuredGrid* InitPointInsertion(
    double center[3], double length, vtkIdType numPts, vtkPoints*& points);
  void InsertPoint(
    vtkUnstructuredGrid* Mesh, vtkPoints* points, vtkIdType id, double x[3], vtkIdList* holeTetras);
  void EndPointInsertion();

  /**
   * The filter's modification time, and its locator's.
   */
  vtkMTimeType GetMTime() override;

  ///@{
  /**
   * Weighted points. The input array to process 0 (SetInputArrayToProcess(0, 0, 0,
   * vtkDataObject::FIELD_ASSOCIATION_POINTS, name); none by default), a point-data array of one
   * component, gives each point a radius r, whose weight is r^2 (WeightsAreRadii, the default, as
   * Voro++ and molecular files give them), or its weight w itself. The output is then the regular
   * (weighted Delaunay) tetrahedralization, for the power distance |x - p|^2 - w. A point whose
   * power cell is empty is hidden: it stays in the output on no cell, NumberOfHiddenPoints counts
   * it, and no warning calls it lost. With Alpha, a simplex is kept when its smallest orthogonal
   * sphere has a squared radius of at most Alpha^2 (the weighted alpha shape: radii r + probe give
   * the molecular surface's). A point of NaN or infinite weight is left out as an invalid one.
   * Density then estimates the density of the vertices (NaN at hidden points). Weights combine
   * with Periodic, and travel with their points across MPI ranks (vtkPFastDelaunay3D).
   */
  vtkSetMacro(WeightsAreRadii, vtkTypeBool);
  vtkGetMacro(WeightsAreRadii, vtkTypeBool);
  vtkBooleanMacro(WeightsAreRadii, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Periodic boxes: Periodic (three switches, x, y and z; all off by default) repeats the points
   * along the axes switched on, across the box that UseInputBounds and Bounds give, and the
   * output is the Delaunay tetrahedralization of the repeated points, each periodic tetrahedron
   * once. A tetrahedron is placed so that together they tile one period: its least vertex is an
   * input point in the box, and a vertex that falls elsewhere (across the box, or an input point
   * outside the box, wrapped into it) is an image point, appended after the input points with a
   * copy of its input point's data. The point array "SourcePointId" names the input point each
   * output point copies (itself for the input's). Where every axis is periodic, the tetrahedra's
   * volumes add up to the box's; along an axis that is not, the tetrahedralization ends at the
   * points' extent. Density is the periodic estimate, from each point's whole star. Any number
   * of points works, one included. Exact duplicates are merged once wrapped, and points too
   * close for the doubles to tell their images apart are skipped (NumberOfSkippedPoints).
   * Tolerance, VolumeThreshold, the Locator and BoundingTriangulation do not apply. Alpha gives
   * the periodic alpha shape: each simplex once, placed as a tetrahedron that holds it, faces and
   * edges followed across the box; its lone vertices are input points. With weights, the
   * regular tetrahedralization of the repeated weighted points (every image with its point's
   * weight), its hidden points on no cell, and the weighted alpha shape. Across MPI ranks
   * (vtkPFastDelaunay3D) each rank outputs its share; with weights the first rank gathers every
   * rank's points and outputs the whole result, as one process would.
   */
  vtkSetVector3Macro(Periodic, vtkTypeBool);
  vtkGetVector3Macro(Periodic, vtkTypeBool);
  ///@}

  ///@{
  /**
   * The box of Periodic: by default (UseInputBounds on) the bounding box of the input's finite
   * points; with UseInputBounds off, Bounds (xmin, xmax, ymin, ymax, zmin, zmax; default the unit
   * cube). A simulation box is usually not its points' bounding box: set it with
   * UseInputBounds off. The box is [min, max) along each periodic axis: a point at its maximum
   * is the same as one at its minimum. A Bounds with a minimum above its maximum or a bound that
   * is not finite is no box: a warning, and the input's bounds are used. Without Periodic, the
   * box is not used.
   */
  vtkSetMacro(UseInputBounds, vtkTypeBool);
  vtkGetMacro(UseInputBounds, vtkTypeBool);
  vtkBooleanMacro(UseInputBounds, vtkTypeBool);
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /**
   * Figures of the last execution: distinct points inserted, exact duplicates merged, points
   * skipped for Tolerance, points with NaN/Inf coordinates (or weight), weighted points hidden,
   * tetrahedra produced; the mean and maximum walk length (tetrahedra visited to locate a point:
   * the paper's "Path"), the mean cavity size (tetrahedra deleted per insertion: the paper's
   * "core"); seconds spent in the kernel, and per phase: sorting the points, locating them, growing
   * the cavities, filling them, and output (the kernel's extraction plus the VTK cell arrays).
   * Locate, cavity and fill times are sampled on one insertion in 16 and scaled up. Each run resets
   * them. The four counts of points that are no vertex are also in the output's field data whenever
   * one of them is not 0 (all figures with ComputeStatistics).
   */
  vtkGetMacro(NumberOfInsertedPoints, vtkIdType);
  vtkGetMacro(NumberOfDuplicatePoints, vtkIdType);
  vtkGetMacro(NumberOfSkippedPoints, vtkIdType);
  vtkGetMacro(NumberOfInvalidPoints, vtkIdType);
  vtkGetMacro(NumberOfHiddenPoints, vtkIdType);
  vtkGetMacro(NumberOfTetrahedra, vtkIdType);
  vtkGetMacro(MeanWalkLength, double);
  vtkGetMacro(MaxWalkLength, vtkIdType);
  vtkGetMacro(MeanCavitySize, double);
  vtkGetMacro(KernelSeconds, double);
  vtkGetMacro(SortSeconds, double);
  vtkGetMacro(LocateSeconds, double);
  vtkGetMacro(CavitySeconds, double);
  vtkGetMacro(FillSeconds, double);
  vtkGetMacro(OutputSeconds, double);
  ///@}

protected:
  vtkFastDelaunay3D();
  ~vtkFastDelaunay3D() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  double Alpha = 0.0;
  vtkTypeBool AlphaTets = 1;
  vtkTypeBool AlphaTris = 1;
  vtkTypeBool AlphaLines = 1;
  vtkTypeBool AlphaVerts = 1;
  double Tolerance = 0.0;
  double Offset = 2.5;
  vtkTypeBool BoundingTriangulation = 0;
  int OutputPointsPrecision = vtkAlgorithm::DEFAULT_PRECISION;
  double GridResolution = 4.0;
  double VolumeThreshold = 0.0;
  int InsertionOrder = BRIO_HILBERT;
  int RandomSeed = 1;
  int NumberOfThreads = 0;
  vtkTypeBool ComputeCircumradius = 0;
  vtkTypeBool ComputeVolume = 0;
  vtkTypeBool ComputeRadiusEdgeRatio = 0;
  vtkTypeBool ComputeDensity = 0;
  vtkTypeBool ComputeStatistics = 0;
  vtkTypeBool WeightsAreRadii = 1;
  vtkTypeBool Periodic[3] = { 0, 0, 0 };
  vtkTypeBool UseInputBounds = 1;
  double Bounds[6] = { 0, 1, 0, 1, 0, 1 };
  vtkSmartPointer<vtkIncrementalPointLocator> Locator;

  vtkIdType NumberOfInsertedPoints = 0;
  vtkIdType NumberOfDuplicatePoints = 0;
  vtkIdType NumberOfSkippedPoints = 0;
  vtkIdType NumberOfInvalidPoints = 0;
  vtkIdType NumberOfHiddenPoints = 0;
  vtkIdType NumberOfTetrahedra = 0;
  double MeanWalkLength = 0.0;
  vtkIdType MaxWalkLength = 0;
  double MeanCavitySize = 0.0;
  double KernelSeconds = 0.0;
  double SortSeconds = 0.0;
  double LocateSeconds = 0.0;
  double CavitySeconds = 0.0;
  double FillSeconds = 0.0;
  double OutputSeconds = 0.0;

  /// Whether a cell (given by its point ids) goes to the output; empty: every cell does.
  using CellFilter = std::function<bool(const std::uint32_t* ids, int size)>;

  fd3::Options KernelOptions(double diagonal);
  /// The kernel's tetrahedralization of the first `count` points of xyz, the input's first
  /// `inputPoints` of them merged by the Locator where there is one; regular where `weights` is
  /// given.
  fd3::Triangulation Triangulate(const double* xyz, const double* weights, std::size_t count,
    vtkIdType inputPoints, const fd3::Bounds& bounds);
  /// The output of a periodic box (Periodic): the periodic tetrahedra of the input's points, or
  /// its alpha shape, and their image points; regular where `weightArray` is given. Returns as
  /// RequestData does.
  int TriangulatePeriodic(
    vtkDataSet* input, vtkUnstructuredGrid* output, vtkDataArray* weightArray);
  /// The weights of the `count` points from `array` (squared where WeightsAreRadii), the input's
  /// first `inputPoints` of them; false, with an error, where they cannot be read.
  bool ReadWeights(
    vtkDataArray* array, vtkIdType inputPoints, std::size_t count, std::vector<double>& weights);
  /// The periodic output: the input's `points` and their `pointData`, the images of `placement`
  /// after them, the tetrahedra or the alpha shape (taking placement.tetrahedra over), Density and
  /// the cell arrays asked for. `xyz`: the kernel's coordinates, of the points and then, in an MPI
  /// rank's piece, of its ghosts, which `pointData` and `density` (with ComputeDensity, a value
  /// per point) cover too, and `ids` (null: the points' indices), which name each output point's
  /// input point in SourcePointId. `owned`, with Alpha, for a rank's placed stars
  /// (fd3::PeriodicPiece::stars): the tetrahedra it owns; of the alpha shape, the rest are not
  /// output, nor the triangles and lines whose least vertex (least id) is no point of the rank's.
  /// `weights` and `hidden`: of a regular tetrahedralization, for the weighted alpha shape.
  void SetPeriodicOutput(vtkUnstructuredGrid* output, vtkPoints* points, vtkPointData* pointData,
    const double* xyz, fd3::PeriodicPlacement& placement, std::vector<double> density,
    const std::uint32_t* ids = nullptr, const std::vector<std::uint8_t>* owned = nullptr,
    const double* weights = nullptr, const std::vector<std::uint32_t>& hidden = {});
  void RecordFigures(const fd3::Statistics& stats);
  /// Warns about what the input made the kernel leave out; false when there is nothing to output.
  /// (`weighted`: the points had weights, whose NaN or Inf leaves a point out too.)
  bool ReportOnInput(fd3::Status status, const fd3::Statistics& stats, vtkIdType numberOfPoints,
    bool weighted = false);
  /// The tetrahedra, or the alpha shape's cells, of `result` (ids into xyz; weighted where
  /// `weights` is given), those that `keep` accepts. Without an alpha shape the output takes
  /// result.tetrahedra over (left empty).
  void SetOutputCells(vtkUnstructuredGrid* output, const double* xyz, const double* weights,
    std::size_t count, fd3::Triangulation& result, const CellFilter& keep = CellFilter());
  /// The alpha shape's cells, as AlphaTets, AlphaTris, AlphaLines and AlphaVerts ask, on the
  /// tetrahedra `tets` (4 point ids each) that shape.tetrahedra indexes.
  void SetAlphaShape(
    vtkUnstructuredGrid* output, const std::uint32_t* tets, const fd3::AlphaComplex& shape);
  /// The requested Circumradius, Volume and RadiusEdgeRatio cell arrays; xyz: the output points.
  void AddCellArrays(vtkUnstructuredGrid* output, const double* xyz);
  /// The Density point array, from `density` for the first output points and NaN for the rest.
  static void AddDensity(vtkUnstructuredGrid* output, const std::vector<double>& density);
  /// The figures as field data: all of them with ComputeStatistics, else the counts of left-out
  /// points whenever some are.
  void AddFigures(vtkFieldData* fields) const;

private:
  /// Sets `property` to `value` clamped to [lo, hi], or to `nan` for NaN.
  void SetClamped(double& property, double value, double lo, double hi, double nan);

  /// The figures above by name, for the field data and PrintSelf.
  struct Figure
  {
    const char* Name;
    double Value;
    bool CountsLeftOutPoints;
  };
  std::vector<Figure> Figures() const;

  /// The Locator's merging of the input's finite points, in input order: for each point, the id
  /// of the one it is merged into, or -1.
  std::vector<vtkIdType> MergeByLocator(const double* xyz, vtkIdType count, const fd3::Bounds& box);

  std::unique_ptr<fd3vtk::PointInsertion> Insertion; ///< between InitPointInsertion and its end

  vtkFastDelaunay3D(const vtkFastDelaunay3D&) = delete;
  void operator=(const vtkFastDelaunay3D&) = delete;
};

#endif
