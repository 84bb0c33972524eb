// Voronoi cells clipped to a box, as the dual of the exact Delaunay tetrahedralization.
// Each cell's faces are the Delaunay edges at its generator (a face's neighbour is the edge's other
// end), each face's vertices the circumcentres of the tetrahedra around that edge: the topology is
// the tetrahedralization's, ties included, so neighbours are symmetric and no face is lost to
// rounding. Coordinates are doubles; a vertex is computed once (a circumcentre per tetrahedron,
// a box crossing from its edge's ends in a fixed order), so the cells that share a face share its
// vertices bit for bit and the volumes add up to the box's.
#ifndef fd3_Voronoi_h
#define fd3_Voronoi_h

#include "fd3/Bounds.h"
#include "fd3/Delaunay.h"
#include "fd3/Distributed.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace fd3
{

/// A face on the box: VoronoiCells::faceNeighbors holds kBoxFace + w for wall w of the box, in
/// VTK's bounds order (xmin, xmax, ymin, ymax, zmin, zmax): wall w lies on axis w / 2, at the box's
/// lo (even w) or hi (odd w).
constexpr std::uint32_t kBoxFace = 0xFFFFFFF0u;

struct VoronoiOptions
{
  /// The clipping box; an empty one (the default) or one with a bound that is not finite is the
  /// bounding box of the finite input points.
  Bounds box;
  /// Threads (0: all hardware threads; bounded as Options::threads). The cells do not depend on it.
  int threads = 1;
  /// As Options::progress, for the tetrahedralization.
  std::function<bool(double)> progress;
  /// How many input points, from the first, get cells (all, by default). The others only bound
  /// those cells: they are the neighbours that the other pieces of a distributed point set send.
  /// A cell is its generator's in the whole set when every Delaunay neighbour of its generator in
  /// the whole set is among the points.
  std::size_t generators = SIZE_MAX;
  /// Whether to give each cell its generator's Delaunay tessellation field estimate (densities():
  /// from the tetrahedralization of the points alone, as triangulate() makes it).
  bool density = false;
  /// Whether to give the cells' polyhedra (points, faceStart, faceVertices, cellPointStart,
  /// cellPoints). Without them each cell still has its faces' neighbours, its volume and its area
  /// (what a Voronoi density, a neighbour graph or a size distribution needs), in about half the
  /// memory.
  bool polyhedra = true;
};

/// One cell per generator: each distinct finite input point (duplicates are merged into the first
/// of their copies, as triangulate() merges them) among the first VoronoiOptions::generators. A
/// generator whose region misses the box has a cell without faces, of volume 0.
struct VoronoiCells
{
  /// Ok, Empty (no finite point), Aborted; or OutOfRange when the points and box span more than
  /// the Voronoi vertices' doubles hold. Anything else leaves no cells.
  Status status = Status::Ok;
  Bounds box; ///< the box the cells were clipped to
  /// The arrays of doubles and of offsets, in the kernel's allocator (no zero fill).
  using Doubles = std::vector<double, BulkAllocator<double>>;
  using Offsets = std::vector<std::size_t, BulkAllocator<std::size_t>>;
  /// The cells' vertices (empty without VoronoiOptions::polyhedra, as are faceStart,
  /// faceVertices, cellPointStart and cellPoints), x,y,z each: the circumcentres in the box, cell
  /// after cell (each cell's own, those of the tetrahedra whose lowest vertex is its generator),
  /// then the crossings of the box, cell after cell (each clipped cell has its own, at the same
  /// coordinates as its neighbours').
  Doubles points;
  /// Each cell's input point id; the cells follow a Hilbert curve through the points, an order
  /// that only the points decide.
  IdArray generators;
  Offsets cellFaces;    ///< cell c's faces: [cellFaces[c], cellFaces[c+1])
  Offsets faceStart;    ///< face f's vertices: [faceStart[f], faceStart[f+1])
  IdArray faceVertices; ///< point ids; counter-clockwise seen from outside
  /// Each cell's vertices, each once: [cellPointStart[c], cellPointStart[c+1]) of cellPoints, ids
  /// of points (what a polyhedral cell type lists beside its faces).
  Offsets cellPointStart;
  IdArray cellPoints;
  /// The input point id of the generator across each face, or kBoxFace + wall.
  IdArray faceNeighbors;
  Doubles volumes, areas; ///< per cell; areas include the box's faces
  /// Per cell, with VoronoiOptions::density: its generator's densities() value (NaN where the
  /// points have no tetrahedron).
  Doubles densities;
  /// Every stretch of work split over the threads, the tetrahedralization's then the cells', in
  /// the order run (Triangulation::threadedWork).
  std::vector<ThreadedWork> threadedWork;
  /// The tetrahedralization's figures for the input's points (the kernel adds eight far points
  /// of its own, not counted here).
  Statistics stats;

  std::size_t numberOfCells() const { return generators.size(); }
  std::size_t numberOfFaces(std::size_t cell) const
  {
    return cellFaces[cell + 1] - cellFaces[cell];
  }
  /// The faces of the cell that are not on the box.
  std::size_t numberOfNeighbors(std::size_t cell) const;
};

/// The Voronoi cells of `count` points (x,y,z triples), clipped to options.box. Throws as
/// triangulate() does.
VoronoiCells voronoiCells(const double* xyz, std::size_t count, const VoronoiOptions& options = {});
/// The power (Laguerre) cells of `count` weighted points, clipped to options.box: the cell of
/// point i holds the x whose power distance |x - p_i|^2 - weights[i] is the least, its faces lie
/// on radical planes, and its vertices are the regular tetrahedralization's orthocentres
/// (triangulate() with weights). A cell may miss its own point. A hidden point's cell is empty:
/// no faces, volume 0; the volumes still fill the box. A point of non-finite weight has no cell,
/// as one of non-finite coordinates. Densities are those of the regular tetrahedralization's
/// vertices (densities()), NaN at hidden points.
VoronoiCells voronoiCells(
  const double* xyz, const double* weights, std::size_t count, const VoronoiOptions& options = {});

/// The cells of a piece of a distributed point set from its mesh, without tetrahedralizing its
/// points again: the mesh took its points (the piece's own first, options.generators of them,
/// then those other pieces sent), all within `pointBounds` (the whole set's bounds, so that every
/// piece adds the same far points), in a frame that also holds voronoiFarPoints(pointBounds,
/// options.box); options.box must be a finite box. The cells are those voronoiCells() gives the
/// same points. Adds the far points and ends the mesh, which gives back its points' coordinates in
/// `xyz` (as IncrementalDelaunay::release does). A weighted mesh gives power cells: `weights` then
/// holds every point's weight, by id, as the mesh was given them, and stats.hiddenPoints counts the
/// generators hidden. Throws as triangulate() does.
VoronoiCells voronoiCells(IncrementalDelaunay& mesh, const Bounds& pointBounds,
  const VoronoiOptions& options, Coordinates& xyz, const double* weights = nullptr);

/// The eight far points (x, y, z each) that the cells of points within `pointBounds`, clipped to
/// `box`, add to the points' tetrahedralization (the corners of a cube about both); empty where
/// they are beyond the doubles.
std::vector<double> voronoiFarPoints(const Bounds& pointBounds, const Bounds& box);

} // namespace fd3

#endif
