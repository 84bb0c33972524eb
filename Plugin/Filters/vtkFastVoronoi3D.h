/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
/**
 * @class   vtkFastVoronoi3D
 * @brief   Voronoi cells of the input points, clipped to a box, as polyhedra
 *
 * vtkFastVoronoi3D outputs one VTK_POLYHEDRON cell per distinct finite input point: the part of
 * that point's Voronoi region (the space nearer to it than to any other point) inside a box
 * (Bounds, or the input's bounds), or its periodic cell (Periodic).
 * The cells are the dual of the exact Delaunay tetrahedralization of vtkFastDelaunay3D: each face
 * is a Delaunay edge, each face vertex the circumcentre of a tetrahedron around it, so the
 * topology is exact, ties (cospherical points, lattices) are broken as the tetrahedralization
 * breaks them, and neighbours are symmetric. Vertex positions and clipping are computed in
 * double; a vertex is computed once, so the cells that share a face share its vertices exactly
 * and the volumes add up to the box's.
 *
 * Cell data: GeneratorId (the input point id), Volume, SurfaceArea (the box's faces included),
 * NumberOfFaces and NumberOfNeighbors (the faces shared with another cell), Density where asked
 * for, and the input's point data, each point's values on its cell. The cells follow a Hilbert
 * curve through the points. Circumcentres are points shared by the cells around them; where a
 * cell is clipped, its crossings of the box are points of its own (at the same coordinates as its
 * neighbours'). The second output holds every face once where asked for (GenerateFaces). With
 * GeneratePolyhedra off, each cell is a VTK_VERTEX at its generator instead, with the same cell
 * data.
 *
 * Use the Volume array: ParaView's own volume of a polyhedron (Integrate Variables, Cell Size) is
 * wrong on some convex cells.
 *
 * As in vtkFastDelaunay3D, exact duplicate points are merged (the first copy's id makes the cell)
 * and points with NaN or infinite coordinates are left out; both are counted, reported in one
 * warning and recorded in the getters and the field data. A point whose region misses the box
 * has an empty cell (VTK_EMPTY_CELL, volume 0), so that cells and distinct points still match.
 *
 * @sa
 * vtkFastDelaunay3D
 */
#ifndef vtkFastVoronoi3D_h
#define vtkFastVoronoi3D_h

#include "FastDelaunay3DFiltersModule.h" // For export macro
#include "vtkSmartPointer.h"             // For the cells' points
#include "vtkUnstructuredGridAlgorithm.h"

#include <cstdint>    // for std::uint32_t
#include <functional> // for std::function

class vtkDataArray;
class vtkDataSet;
class vtkFieldData;
class vtkPointData;
class vtkPoints;
class vtkPolyData;
namespace fd3
{
enum class Status;
struct Bounds;
struct VoronoiCells;
struct VoronoiOptions;
class Workers;
} // namespace fd3

class FASTDELAUNAY3DFILTERS_EXPORT vtkFastVoronoi3D : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkFastVoronoi3D* New();
  vtkTypeMacro(vtkFastVoronoi3D, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The box: by default (UseInputBounds on) the bounding box of the input's finite points; with
   * UseInputBounds off, Bounds (xmin, xmax, ymin, ymax, zmin, zmax; default the unit cube). The
   * cells are clipped to it. A Bounds with a minimum above its maximum or a bound that is not
   * finite is no box: a warning, and the input's bounds are used. A box of no volume (coplanar
   * points with the input's bounds) gives empty cells.
   */
  vtkSetMacro(UseInputBounds, vtkTypeBool);
  vtkGetMacro(UseInputBounds, vtkTypeBool);
  vtkBooleanMacro(UseInputBounds, vtkTypeBool);
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /**
   * Periodic boxes: Periodic (three switches, x, y and z; all off by default) repeats the points
   * along the axes switched on, across the box, [min, max) on each (a simulation box is usually
   * not its points' bounding box: set Bounds with UseInputBounds off). Each distinct point then
   * has its periodic cell once, a polyhedron around the point's place in the box (an input point
   * outside the box is wrapped into it), whole across the box's periodic sides and clipped to it
   * along the other axes. Where every axis is periodic, the volumes add up to the box's.
   * NumberOfNeighbors counts the neighbours across the box's sides, and a face's neighbour may
   * be the cell's own point (a box of few points). Density is the periodic estimate, from whole
   * stars. With weights, the periodic power cells (a hidden point's empty), still filling the
   * box. Across MPI ranks (vtkPFastVoronoi3D) each rank outputs its own points' cells; with
   * weights the first rank gathers every rank's points and outputs every cell, as one process
   * would.
   */
  vtkSetVector3Macro(Periodic, vtkTypeBool);
  vtkGetVector3Macro(Periodic, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Number of threads. 0 (the default) uses what vtkSMPTools::GetEstimatedNumberOfThreads()
   * reports. The cells are the same for any number. At most 4 threads per hardware thread (or 64
   * where that is more) are started.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * When on, a cell array "Density": each generator's Delaunay tessellation field estimate, as
   * vtkFastDelaunay3D's ComputeDensity gives it (where points are cospherical, its tie-breaks may
   * pick other tetrahedra, with the same total). Off by default.
   */
  vtkSetMacro(ComputeDensity, vtkTypeBool);
  vtkGetMacro(ComputeDensity, vtkTypeBool);
  vtkBooleanMacro(ComputeDensity, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Weighted points, as vtkFastDelaunay3D takes them: the input array to process 0 (none by
   * default), a point array of radii (WeightsAreRadii, the default: weight r^2) or weights, gives
   * each point's power (Laguerre, radical) cell, of the points x whose power distance
   * |x - p|^2 - w is the least, as Voro++'s container_poly computes them. A cell may miss its own
   * point; a hidden point's cell is empty (no faces, volume 0; NumberOfHiddenPoints counts them),
   * and the volumes still fill the box. Density is then that of the regular tetrahedralization's
   * vertices (NaN at hidden points). Weights combine with Periodic, and travel with their
   * points across MPI ranks (vtkPFastVoronoi3D).
   */
  vtkSetMacro(WeightsAreRadii, vtkTypeBool);
  vtkGetMacro(WeightsAreRadii, vtkTypeBool);
  vtkBooleanMacro(WeightsAreRadii, vtkTypeBool);
  ///@}

  ///@{
  /**
   * When on (the default), each cell is its Voronoi polyhedron, a VTK_POLYHEDRON. When off, each
   * cell is a VTK_VERTEX at its generator (the input point) with the same cell data: every
   * point's Voronoi volume, area and neighbours in a small part of the polyhedra's memory.
   */
  vtkSetMacro(GeneratePolyhedra, vtkTypeBool);
  vtkGetMacro(GeneratePolyhedra, vtkTypeBool);
  vtkBooleanMacro(GeneratePolyhedra, vtkTypeBool);
  ///@}

  ///@{
  /**
   * When on, the second output (port 1, a vtkPolyData on the polyhedra's points) holds every
   * face once, as a polygon: a face that two cells share, from the cell of the lower GeneratorId,
   * and each face on the box. Cell data: "GeneratorIds", its two generators' input ids (-1 for
   * the box's side), and "Area". Off by default: the second output is then empty.
   */
  vtkSetMacro(GenerateFaces, vtkTypeBool);
  vtkGetMacro(GenerateFaces, vtkTypeBool);
  vtkBooleanMacro(GenerateFaces, vtkTypeBool);
  ///@}

  /**
   * The faces (port 1; see GenerateFaces).
   */
  vtkPolyData* GetFacesOutput();

  ///@{
  /**
   * Figures of the last run: the distinct finite points (one cell each), the exact duplicates
   * merged, the points with NaN or infinite coordinates (or weight) left out, and the weighted
   * points hidden (an empty cell each).
   */
  vtkGetMacro(NumberOfGenerators, vtkIdType);
  vtkGetMacro(NumberOfDuplicatePoints, vtkIdType);
  vtkGetMacro(NumberOfInvalidPoints, vtkIdType);
  vtkGetMacro(NumberOfHiddenPoints, vtkIdType);
  ///@}

  ///@{
  /**
   * Wall-clock seconds of the last run: the kernel's cells (tetrahedralization included; under
   * MPI this rank's, with the exchanges), and the writing of the outputs' arrays from them.
   */
  vtkGetMacro(KernelSeconds, double);
  vtkGetMacro(ConversionSeconds, double);
  ///@}

protected:
  vtkFastVoronoi3D();
  ~vtkFastVoronoi3D() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// The cells of `input`'s points (power cells with `weightArray`), written to `output` and
  /// `faces`. Returns as RequestData does.
  int OutputCells(
    vtkDataSet* input, vtkDataArray* weightArray, vtkUnstructuredGrid* output, vtkPolyData* faces);
  /// The kernel's options from the properties, with progress and abort for the tetrahedralization;
  /// the box is `inputBounds` where UseInputBounds says so, and without them the kernel's own
  /// bounds of the points.
  fd3::VoronoiOptions KernelOptions(const fd3::Bounds& inputBounds);
  fd3::VoronoiOptions KernelOptions();
  /// The cells of the serial filter: periodic where Periodic says so. Throws as the kernel does,
  /// and std::invalid_argument, saying why, where there can be no periodic cells.
  fd3::VoronoiCells ComputeCells(const double* xyz, const double* weights, std::size_t count);
  /// Records the figures (of every rank, under MPI).
  void RecordFigures(
    vtkIdType generators, vtkIdType duplicates, vtkIdType invalid, vtkIdType hidden = 0);
  /// Warns of what the figures say was left out, or why there are no cells (`status`, of the
  /// kernel, `box`, the box the cells were clipped to); false when there are no cells to output.
  bool ReportOnInput(
    fd3::Status status, const fd3::Bounds& box, vtkIdType numberOfPoints, bool weighted = false);
  /// The first output's points and cells, polyhedra or generators as GeneratePolyhedra says
  /// (`xyz`: the points the kernel was given), written on `workers`; returns the polyhedra's
  /// points, which the faces are on (null where the kernel made no polyhedra). The cells' points
  /// and cellPoints are handed over to the output.
  vtkSmartPointer<vtkPoints> SetGeometry(vtkUnstructuredGrid* output, fd3::VoronoiCells& cells,
    const double* xyz, fd3::Workers& workers) const;
  /// A VTK_VERTEX cell at each cell's generator.
  static void SetGenerators(vtkUnstructuredGrid* output, const fd3::VoronoiCells& cells,
    const double* xyz, fd3::Workers& workers);
  /// GeneratorId, Volume, SurfaceArea, NumberOfFaces, NumberOfNeighbors and the input's point
  /// data on the cells.
  static void AddCellData(vtkUnstructuredGrid* output, const fd3::VoronoiCells& cells,
    vtkPointData* pointData, fd3::Workers& workers);
  /// Every face once into `faces`, on the cells' `points`; `inputId` maps the kernel's point ids
  /// (a generator's, a face's neighbour's) to input ids.
  static void SetFaces(vtkPolyData* faces, const fd3::VoronoiCells& cells, vtkPoints* points,
    const std::function<vtkIdType(std::uint32_t)>& inputId);
  /// The counts of left-out points as field data, where there are some.
  void AddFigures(vtkFieldData* fields) const;

  vtkTypeBool UseInputBounds = 1;
  double Bounds[6] = { 0, 1, 0, 1, 0, 1 };
  vtkTypeBool Periodic[3] = { 0, 0, 0 };
  int NumberOfThreads = 0;
  vtkTypeBool ComputeDensity = 0;
  vtkTypeBool GeneratePolyhedra = 1;
  vtkTypeBool GenerateFaces = 0;
  vtkTypeBool WeightsAreRadii = 1;
  vtkIdType NumberOfGenerators = 0;
  vtkIdType NumberOfDuplicatePoints = 0;
  vtkIdType NumberOfInvalidPoints = 0;
  vtkIdType NumberOfHiddenPoints = 0;
  double KernelSeconds = 0.0;
  double ConversionSeconds = 0.0;

private:
  vtkFastVoronoi3D(const vtkFastVoronoi3D&) = delete;
  void operator=(const vtkFastVoronoi3D&) = delete;
};

#endif
