// Voronoi cells clipped to a box, from the exact Delaunay tetrahedralization.
//
// 1. The points are copied along a Hilbert curve, and eight far points, the corners of a cube
//    around the points and the box, join them: then every generator lies inside the hull, so its
//    cell is bounded and every ring of tetrahedra about one of its edges is closed. A box point x
//    is never nearer a far point f than its own generator p: |x - p| <= D, the diagonal of the
//    points and box together, while the corners lie at least 2 sqrt(3) D - D/2 > D from x. So
//    each cell's part inside the box is unchanged, and every face with a far point lies outside
//    the box.
// 2. Each tetrahedron's vertices are put in ascending order (orientation kept), and the
//    tetrahedra of generators are grouped by their lowest vertex, a generator (they come first
//    along the curve), each group ordered by the other three: an order that the points alone
//    decide (the mesh's own varies with the thread count). A tetrahedron's circumcentre is
//    computed once, from its vertices in that order (in double-double where it is flat); a
//    group's centres in the box are its cell's own, numbered in the groups' order.
// 3. The stars: a vertex's own group, then the tetrahedra of lower vertices' groups that hold it,
//    listed in two passes (a count, then the ids), each thread keeping the vertices of its own
//    range; beside them, whether any centre of its star lies outside the box.
// 4. A cell's faces, per generator p: the ring of its star's tetrahedra about each edge (p, q),
//    turning counter-clockwise about p -> q, so the face is counter-clockwise seen from outside.
//    The faces go in the order the star meets their q, each ring from the last of the star's
//    tetrahedra in it: both follow from the star's order, the points' alone, so the cells do not
//    depend on the thread count or on how the generators are split among the threads.
// 5. The cells that leave the box first, on the threads: clipped by the box's six planes, each
//    face keeps its inside part, a crossing of an edge is computed from its two ends taken in
//    lexicographic order and put exactly on the plane (so the cells around that edge compute the
//    same point), and the crossings close a new face on the plane. With their sizes known (a
//    whole cell with a star of n tetrahedra has 2 + n/2 faces and 3n face vertices), every cell
//    has its place in the output: the centres each cell owns are numbered there, and the whole
//    cells are written straight into their places. Volume and surface area come from each face's
//    Newell vector. Without polyhedra (VoronoiOptions::polyhedra), the cells are traced and
//    clipped alike, but only their faces' neighbours, volumes and areas are written.
#include "fd3/Voronoi.h"

#include "FiniteBounds.h"
#include "fd3/Bounds.h"
#include "fd3/Distributed.h"
#include "insertion/InsertionOrder.h"
#include "system/Threads.h"
#include "voronoi/BoxClip.h"
#include "voronoi/CellBuilder.h"
#include "voronoi/Circumcentres.h"
#include "voronoi/Stars.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>

namespace fd3
{
namespace
{
using namespace voronoi;
constexpr int kFarPoints = 8;

/// The input's points along a Hilbert curve through their bounding box (exact copies in the
/// order of their ids): the generators, then the points that only bound their cells (so that a
/// tetrahedron with a generator has one as its lowest vertex, the owner of its centre), then the
/// points that are not finite; then the corners of a cube about the points and the box (see the
/// top of this file). Neighbouring points, and so the tetrahedra between them, then lie near each
/// other in memory.
struct CurvePoints
{
  VoronoiCells::Doubles xyz; ///< empty when the corners are not finite
  IdArray inputId;           ///< of each point but the corners
  /// Weighted points: each one's weight, the corners' the least finite one (see the top of this
  /// file: no box point is then nearer a corner in power than its own generator); else empty.
  VoronoiCells::Doubles weights;
};

/// The far points' weight: the least finite one of `count` weights (0 where none), so that no
/// point in the box is nearer a far point in power than its own generator.
double farWeight(const double* weights, std::size_t count)
{
  double least = HUGE_VAL;
  for (std::size_t i = 0; i < count; ++i)
    if (std::isfinite(weights[i]))
      least = std::min(least, weights[i]);
  return std::isfinite(least) ? least : 0.0;
}

CurvePoints alongCurve(ThreadTeam& team, const double* xyz, const double* weights,
  std::size_t count, std::size_t generators, const Bounds& points, const Bounds& box)
{
  const double cells = double(1u << kHilbertBits);
  double scale[3];
  for (int a = 0; a < 3; ++a)
  {
    const double extent = points.extent(a);
    scale[a] = extent > 0 && std::isfinite(extent) ? cells / extent : 0;
  }
  const std::vector<double> far = voronoiFarPoints(points, box);
  if (far.empty())
    return {};
  CurvePoints curve;
  curve.xyz.resize(3 * (count + kFarPoints));
  std::copy(far.begin(), far.end(), curve.xyz.begin() + std::ptrdiff_t(3 * count));
  Words keys(count); // position along the curve << 32 | id
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const double* p = xyz + 3 * i;
      // Not finite: after every finite point.
      std::uint64_t position = std::uint64_t(1) << (3 * kHilbertBits + 1);
      if (isFinite(p))
      {
        std::uint32_t cell[3];
        for (int a = 0; a < 3; ++a)
          cell[a] = static_cast<std::uint32_t>(
            std::min(cells - 1, std::max(0.0, (p[a] - points.lo[a]) * scale[a])));
        position = hilbertIndex(cell[0], cell[1], cell[2]);
        if (i >= generators) // after every generator: see circumcentres' owners
          position |= std::uint64_t(1) << (3 * kHilbertBits);
      }
      keys[i] = position << 32 | i;
    }
  });
  radixSortByHighHalf(keys, 3 * kHilbertBits + 2, &team);
  curve.inputId.resize(count);
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const auto id = static_cast<std::uint32_t>(keys[k]);
      curve.inputId[k] = id;
      for (int a = 0; a < 3; ++a)
        curve.xyz[3 * k + a] = xyz[3 * std::size_t(id) + a];
    }
  });
  team.release(keys, "voronoi curve");
  if (weights)
  {
    curve.weights.resize(count + kFarPoints, farWeight(weights, count));
    for (std::size_t k = 0; k < count; ++k)
      curve.weights[k] = weights[curve.inputId[k]];
  }
  return curve;
}

/// The tetrahedralization of the points, then of the far points, in one frame. Inserted last,
/// the far points meet the points' hull in a few tests; inserted among the points, they would take
/// part in the tests of every insertion near the hull, in exact arithmetic where its faces hold
/// cocircular points (a lattice's), which no sphere through a far point tells apart. With
/// options.density, `density` gets each point's densities() value in the points' own
/// tetrahedralization, before the far points change the tetrahedra near the hull.
Triangulation meshOf(const CurvePoints& curve, std::size_t count, const VoronoiOptions& options,
  std::vector<double>& density)
{
  Options delaunay;
  delaunay.threads = options.threads;
  delaunay.progress = options.progress;
  delaunay.computeNeighbors = false; // the stars are listed instead
  const double* weights = curve.weights.empty() ? nullptr : curve.weights.data();
  Frame frame = frameOf(curve.xyz.data(), count + kFarPoints);
  if (weights && !weightsFitFrame(frame, weights, count + kFarPoints))
    frame = identityFrame(frame.bounds);
  IncrementalDelaunay mesh(curve.xyz.data(), count, delaunay, frame, kFarPoints, weights);
  if (mesh.status() == Status::Aborted)
    return mesh.release();
  if (options.density)
    density = densities(curve.xyz.data(), count, mesh.snapshot());
  mesh.add(curve.xyz.data() + 3 * count, kFarPoints, weights ? weights + count : nullptr);
  return mesh.release();
}

/// The generators as the mesh numbers them (the points of the first `generators` ids that are
/// vertices, not merged into another), ascending, and the indices among them of the clipped
/// cells.
void listGenerators(ThreadTeam& team, const Triangulation& mesh, const IdArray& inputId,
  std::size_t generators, const Stars& stars, IdArray& vertices, IdArray& clipped)
{
  ThreadedWork& record = team.newRecord("voronoi generators");
  vertices = team.indicesWhere(record, 0, inputId.size(),
    [&](std::size_t v) { return mesh.representative[v] == v && inputId[v] < generators; });
  clipped = team.indicesWhere(
    record, 0, vertices.size(), [&](std::size_t c) { return stars.clipped[vertices[c]] != 0; });
}

/// Where each cell's parts go in the output: its first face vertex and crossing (its first face
/// is cellFaces', its centres are numbered by numberCentres).
struct CellPlaces
{
  VoronoiCells::Offsets vertex, crossing;
};

/// The sizes of the cells (those of the clipped ones from their stretches; a whole cell with a
/// star of n tetrahedra has 2 + n/2 faces, those of its link, a sphere, 3n face vertices and n
/// points), summed into places, and the output's arrays made to hold them.
CellPlaces placeCells(ThreadTeam& team, const IdArray& vertices, const Stars& stars,
  const IdArray& pointOf, const std::vector<Stretch>& parts, VoronoiCells& cells)
{
  const std::size_t n = vertices.size();
  CellPlaces at;
  at.vertex.resize(n + 1);
  at.crossing.resize(n + 1);
  cells.cellFaces.resize(n + 1);
  const bool polyhedra = !pointOf.empty();
  cells.cellPointStart.resize(polyhedra ? n + 1 : 0);
  // Each cell's sizes after its place, then their running sums. The crossings are numbered after
  // the centres that the cells own.
  cells.cellFaces[0] = at.vertex[0] = 0;
  if (polyhedra)
    cells.cellPointStart[0] = 0;
  at.crossing[0] = n && !pointOf.empty() ? pointOf[stars.ownStart[vertices[n - 1] + 1]] : 0;
  team.forRanges(n, "voronoi places", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
      if (const std::uint32_t p = vertices[c]; !stars.clipped[p])
      {
        const std::size_t star = stars.sizeOf(p); // 0 for a hidden point: no faces
        cells.cellFaces[c + 1] = star ? 2 + star / 2 : 0;
        at.vertex[c + 1] = 3 * star;
        at.crossing[c + 1] = 0;
        if (polyhedra)
          cells.cellPointStart[c + 1] = star;
      }
  });
  team.run(
    parts.size(),
    [&](std::size_t k) {
      const Stretch& s = parts[k];
      auto face = s.faceSizes.begin();
      for (std::size_t j = 0; j < s.cells.size(); ++j)
      {
        const std::size_t c = s.cells[j];
        cells.cellFaces[c + 1] = s.faceCounts[j];
        at.vertex[c + 1] = std::accumulate(face, face + s.faceCounts[j], std::size_t(0));
        at.crossing[c + 1] = s.crossings[j];
        if (polyhedra)
          cells.cellPointStart[c + 1] = s.pointCounts[j];
        face += s.faceCounts[j];
      }
    },
    team.newRecord("voronoi places"));
  team.accumulate(cells.cellFaces, "voronoi places");
  team.accumulate(at.vertex, "voronoi places");
  team.accumulate(at.crossing, "voronoi places");
  if (polyhedra)
    team.accumulate(cells.cellPointStart, "voronoi places");
  cells.faceNeighbors.resize(cells.cellFaces[n]);
  cells.volumes.resize(n);
  cells.areas.resize(n);
  if (!polyhedra)
  {
    cells.faceStart.clear();
    return at;
  }
  const std::size_t points = at.crossing[n];
  if (points >= kOwnVertex)
    throw std::length_error("voronoiCells: more than 2^31 vertices");
  cells.faceStart.resize(cells.cellFaces[n] + 1);
  cells.faceStart[cells.cellFaces[n]] = at.vertex[n];
  cells.faceVertices.resize(at.vertex[n]);
  cells.cellPoints.resize(cells.cellPointStart[n]);
  cells.points.resize(3 * points);
  return at;
}

/// The clipped cells' stretches into the output, their circumcentres numbered through pointOf
/// (empty without polyhedra).
void copyClipped(ThreadTeam& team, std::vector<Stretch>& parts, const CellPlaces& at,
  const IdArray& pointOf, VoronoiCells& cells)
{
  team.run(
    parts.size(),
    [&](std::size_t k) {
      const Stretch& s = parts[k];
      std::size_t face = 0, vertex = 0, point = 0;
      for (std::size_t j = 0; j < s.cells.size(); ++j)
      {
        const std::size_t c = s.cells[j];
        // A vertex as the stretch names it: a tetrahedron (its centre) or one of c's crossings.
        const auto outputId = [&](std::uint32_t id) {
          return id & kOwnVertex ? static_cast<std::uint32_t>(at.crossing[c] + (id & ~kOwnVertex))
                                 : pointOf[id];
        };
        if (!pointOf.empty())
          for (std::size_t i = 0; i < s.pointCounts[j]; ++i, ++point)
            cells.cellPoints[cells.cellPointStart[c] + i] = outputId(s.points[point]);
        std::size_t outFace = cells.cellFaces[c], outVertex = at.vertex[c];
        for (std::uint32_t f = 0; f < s.faceCounts[j]; ++f, ++face, ++outFace)
        {
          cells.faceNeighbors[outFace] = s.neighbors[face];
          if (pointOf.empty()) // no polyhedra
            continue;
          cells.faceStart[outFace] = outVertex;
          for (std::uint32_t i = 0; i < s.faceSizes[face]; ++i, ++vertex)
            cells.faceVertices[outVertex++] = outputId(s.vertices[vertex]);
        }
        cells.volumes[c] = s.volumes[j];
        cells.areas[c] = s.areas[j];
      }
      std::size_t crossing = 0;
      for (std::size_t j = 0; j < s.cells.size(); ++j)
      {
        const std::size_t c = s.cells[j], size = 3 * s.crossings[j];
        std::copy_n(
          s.crossingPoints.data() + crossing, size, cells.points.data() + 3 * at.crossing[c]);
        crossing += size;
      }
      parts[k] = Stretch();
    },
    team.newRecord("voronoi clipped"));
}
/// The tetrahedra's vertices and the representatives of a mesh of points in their input order
/// (the far points last), in the curve's ids instead (inputId: the input id at each place).
void renumberAlongCurve(ThreadTeam& team, const IdArray& inputId, Triangulation& mesh)
{
  const std::size_t count = inputId.size();
  IdArray place(count + kFarPoints);
  team.forRanges(count, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
      place[inputId[k]] = static_cast<std::uint32_t>(k);
  });
  for (std::size_t k = count; k < count + kFarPoints; ++k)
    place[k] = static_cast<std::uint32_t>(k);
  std::uint32_t* t4 = mesh.tetrahedra.data();
  team.forRanges(
    mesh.tetrahedra.size(), "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        t4[i] = place[t4[i]];
    });
  IdArray representative(mesh.representative.size());
  team.forRanges(
    count + kFarPoints, "voronoi curve", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k)
      {
        const std::uint32_t id = k < count ? inputId[k] : static_cast<std::uint32_t>(k);
        const std::uint32_t r = mesh.representative[id];
        representative[k] = r == kNoPoint ? kNoPoint : place[r];
      }
    });
  mesh.representative.swap(representative);
}

/// How many places along the curve hold the finite generators, which come first: only their
/// tetrahedra make cells.
std::size_t ownerCount(const CurvePoints& curve, std::size_t count, const VoronoiOptions& options)
{
  auto owns = [&](std::size_t place) {
    return curve.inputId[place] < options.generators && isFinite(curve.xyz.data() + 3 * place);
  };
  std::size_t lo = 0, hi = count; // owns() holds below lo and fails from hi on
  while (lo < hi)
  {
    const std::size_t mid = lo + (hi - lo) / 2;
    if (owns(mid))
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/// The cells from the tetrahedralization of the points along the curve and the far points (in
/// the curve's ids), with each point's density in the curve's order where asked for.
VoronoiCells cellsOf(ThreadTeam& team, CurvePoints curve, std::size_t count,
  const VoronoiOptions& options, Triangulation mesh, const std::vector<double>& density,
  VoronoiCells cells)
{
  cells.stats = mesh.stats;
  cells.stats.inputPoints -= kFarPoints;
  cells.stats.insertedPoints -= kFarPoints;
  if (mesh.status != Status::Ok)
  {
    cells.status = mesh.status;
    return cells;
  }

  sortVertices(team, mesh);
  Stars stars;
  groupByLowestVertex(team, mesh, count + kFarPoints, ownerCount(curve, count, options), stars);
  Doubles centres;
  Flags inBox;
  circumcentres(team, curve.xyz.data(), curve.weights.empty() ? nullptr : curve.weights.data(),
    stars.tetrahedra, cells.box, centres, inBox);
  listOthers(team, inBox, stars);
  IdArray pointOf = options.polyhedra ? numberCentres(team, inBox) : IdArray();
  IdArray vertices, clipped;
  listGenerators(team, mesh, curve.inputId, options.generators, stars, vertices, clipped);
  cells.generators.resize(vertices.size());
  if (options.density)
    cells.densities.resize(vertices.size());
  team.forRanges(
    vertices.size(), "voronoi cells", [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c)
      {
        cells.generators[c] = curve.inputId[vertices[c]];
        if (options.density)
          cells.densities[c] = density[vertices[c]];
      }
    });

  // The clipped cells first: their sizes are known once they are clipped.
  CellSources sources{curve.xyz.data(), curve.inputId, stars, cells.box, options.polyhedra};
  sources.centres = centres.data();
  // A builder per thread, kept for both passes.
  std::vector<std::unique_ptr<CellBuilder>> builders(team.size());
  auto builder = [&](std::size_t k) -> CellBuilder& {
    if (!builders[k])
      builders[k] = std::make_unique<CellBuilder>(sources, count + kFarPoints);
    return *builders[k];
  };
  std::vector<Stretch> parts(team.partsFor(clipped.size()));
  team.forRanges(clipped.size(), "voronoi clipped cells",
    [&](std::size_t k, std::size_t begin, std::size_t end) {
      CellBuilder& cell = builder(k);
      for (std::size_t i = begin; i < end; ++i)
      {
        const std::uint32_t p = vertices[clipped[i]];
        cell.trace(p);
        cell.emitClipped(p, clipped[i], parts[k]);
      }
    });
  const CellPlaces at = placeCells(team, vertices, stars, pointOf, parts, cells);
  if (options.polyhedra)
  {
    if (!vertices.empty())
      copyCentres(team, stars.ownStart[vertices.back() + 1], inBox, pointOf, centres, cells);
    team.release(centres, "voronoi centres");
    sources.centres = nullptr;
    sources.pointOf = pointOf.data();
    sources.points = cells.points.data();
  }

  // The whole cells, straight into their places, then the clipped ones.
  team.forRanges(
    vertices.size(), "voronoi cells", [&](std::size_t k, std::size_t begin, std::size_t end) {
      CellBuilder& cell = builder(k);
      for (std::size_t c = begin; c < end; ++c)
      {
        const std::uint32_t p = vertices[c];
        if (stars.clipped[p])
          continue;
        if (stars.sizeOf(p) == 0) // hidden: an empty power cell
        {
          cells.volumes[c] = cells.areas[c] = 0;
          continue;
        }
        cell.trace(p);
        if (options.polyhedra)
          cell.emitWhole<true>(p, c, cells.cellFaces[c], at.vertex[c], cells);
        else
          cell.emitWhole<false>(p, c, cells.cellFaces[c], at.vertex[c], cells);
      }
    });
  copyClipped(team, parts, at, pointOf, cells);
  // What the cells came from, its pages given back on every thread: on return, one thread would.
  team.release(centres, "voronoi release");
  team.release(pointOf, "voronoi release");
  team.release(stars.tetrahedra, "voronoi release");
  team.release(stars.others, "voronoi release");
  team.release(curve.xyz, "voronoi release");
  cells.threadedWork = std::move(mesh.threadedWork);
  const std::vector<ThreadedWork> records = team.records();
  cells.threadedWork.insert(cells.threadedWork.end(), records.begin(), records.end());
  return cells;
}

} // namespace

std::size_t VoronoiCells::numberOfNeighbors(std::size_t cell) const
{
  return static_cast<std::size_t>(std::count_if(faceNeighbors.begin() + cellFaces[cell],
    faceNeighbors.begin() + cellFaces[cell + 1], [](std::uint32_t q) { return q < kBoxFace; }));
}

VoronoiCells voronoiCells(const double* xyz, std::size_t count, const VoronoiOptions& options)
{
  return voronoiCells(xyz, nullptr, count, options);
}

VoronoiCells voronoiCells(
  const double* xyz, const double* weights, std::size_t count, const VoronoiOptions& options)
{
  VoronoiCells cells;
  cells.cellFaces.assign(1, 0);
  cells.faceStart.assign(1, 0);
  cells.cellPointStart.assign(1, 0);
  cells.stats.inputPoints = count;
  ThreadTeam team(boundedThreads(options.threads));
  const Bounds bounds = finiteBounds(team, "voronoi curve", xyz, count);
  if (bounds.empty())
  {
    cells.status = Status::Empty;
    cells.stats.nonFinitePoints = count;
    return cells;
  }
  cells.box = options.box.finite() ? options.box : bounds;
  CurvePoints curve = alongCurve(team, xyz, weights, count, options.generators, bounds, cells.box);
  if (curve.xyz.empty())
  {
    cells.status = Status::OutOfRange;
    return cells;
  }

  std::vector<double> density;
  Triangulation mesh = meshOf(curve, count, options, density);
  return cellsOf(
    team, std::move(curve), count, options, std::move(mesh), density, std::move(cells));
}

VoronoiCells voronoiCells(IncrementalDelaunay& mesh, const Bounds& pointBounds,
  const VoronoiOptions& options, Coordinates& xyz, const double* weights)
{
  VoronoiCells cells;
  cells.cellFaces.assign(1, 0);
  cells.faceStart.assign(1, 0);
  cells.cellPointStart.assign(1, 0);
  const Status before = mesh.status();
  if (before == Status::Empty || before == Status::Aborted) // no finite point, whatever the box
  {
    cells.stats = mesh.release(xyz).stats;
    cells.status = before;
    return cells;
  }
  if (!options.box.finite())
    throw std::invalid_argument("fd3::voronoiCells: the clipping box of a mesh's cells is empty");
  cells.box = options.box;
  ThreadTeam team(boundedThreads(options.threads));
  const std::vector<double> far = voronoiFarPoints(pointBounds, cells.box);
  if (far.empty())
  {
    cells.stats = mesh.release(xyz).stats;
    cells.status = Status::OutOfRange;
    return cells;
  }
  // The densities come from the points' own tetrahedra, before the far points change those at
  // the hull.
  Triangulation own;
  if (options.density)
    own = mesh.snapshot();
  const std::vector<double> farWeights(
    weights ? kFarPoints : 0, weights ? farWeight(weights, mesh.pointCount()) : 0.0);
  mesh.add(far.data(), kFarPoints, weights ? farWeights.data() : nullptr);
  Triangulation tetrahedra = mesh.release(xyz);
  const std::size_t count = xyz.size() / 3 - kFarPoints;
  CurvePoints curve =
    alongCurve(team, xyz.data(), weights, count, options.generators, pointBounds, cells.box);
  std::vector<double> density;
  if (options.density)
  {
    const std::vector<double> byPoint = densities(xyz.data(), count, own);
    own = Triangulation();
    density.resize(count);
    for (std::size_t k = 0; k < count; ++k)
      density[k] = byPoint[curve.inputId[k]];
  }
  xyz.resize(3 * count);
  const auto hiddenGenerators = static_cast<std::size_t>(std::count_if(tetrahedra.hidden.begin(),
    tetrahedra.hidden.end(), [&](std::uint32_t id) { return id < options.generators; }));
  renumberAlongCurve(team, curve.inputId, tetrahedra);
  cells = cellsOf(
    team, std::move(curve), count, options, std::move(tetrahedra), density, std::move(cells));
  cells.stats.hiddenPoints = hiddenGenerators;
  return cells;
}

std::vector<double> voronoiFarPoints(const Bounds& pointBounds, const Bounds& box)
{
  Bounds both = pointBounds;
  both.include(box);
  double centre[3];
  for (int a = 0; a < 3; ++a)
    centre[a] = both.lo[a] / 2 + both.hi[a] / 2;
  double reach = 2 * both.diagonal();
  if (reach == 0)
    reach = 1; // one point and a box of no volume: any cube will do
  std::vector<double> far(3 * kFarPoints);
  for (int k = 0; k < kFarPoints; ++k)
    for (int a = 0; a < 3; ++a)
    {
      const double x = centre[a] + ((k >> a) & 1 ? reach : -reach);
      if (!std::isfinite(x))
        return {};
      far[3 * std::size_t(k) + a] = x;
    }
  return far;
}

} // namespace fd3
