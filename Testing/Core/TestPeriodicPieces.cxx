// A periodic point set split into pieces by space, as the MPI filters split it over their ranks
// (fd3::PeriodicPiece): each piece gets the points of the others with an image within its halo,
// widens the halo where its certificate asks, and the pieces together give exactly what one
// process gives the whole set: every periodic tetrahedron once, the same densities and cells.
// The pieces run here one after the other, the exchange being a filter over the whole set.
#include "PointSets.h"
#include "fd3/Periodic.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace
{
using fd3test::Points;

/// A periodic tetrahedron as a sorted list of its vertices (input id, then offset): the same
/// whatever order a run gives them in.
using Vertices = std::array<std::array<std::int64_t, 4>, 4>;

std::vector<Vertices> sortedTetrahedra(
  const fd3::PeriodicTriangulation& t, const std::vector<std::uint32_t>& ids)
{
  std::vector<Vertices> out(t.numberOfTetrahedra());
  for (std::size_t c = 0; c < out.size(); ++c)
  {
    for (int i = 0; i < 4; ++i)
    {
      out[c][i][0] = ids[t.tetrahedra[4 * c + i]];
      for (int k = 0; k < 3; ++k)
        out[c][i][k + 1] = t.offsets[12 * c + 3 * i + k];
    }
    std::sort(out[c].begin(), out[c].end());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The volume of a piece's tetrahedra placed: its `own` points keep their places, ghosts and
/// images are moved.
double placedVolume(const Points& xyz, std::size_t own, const fd3::PeriodicTriangulation& t,
  const fd3::PeriodicBox& box)
{
  const fd3::PeriodicPlacement placed = fd3::placePeriodic(xyz.data(), own, t, box);
  double volume = 0;
  for (std::size_t c = 0; c < placed.tetrahedra.size(); c += 4)
  {
    const double* v[4];
    for (int i = 0; i < 4; ++i)
    {
      const std::uint32_t id = placed.tetrahedra[c + i];
      v[i] = id < own ? &xyz[3 * id] : &placed.imagePoints[3 * (id - own)];
    }
    double e[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        e[i][k] = v[i + 1][k] - v[0][k];
    volume += (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
      6;
  }
  return volume;
}

/// The pieces' own points: `pieces` slabs of equal counts along x, then halved along y where
/// asked, by place.
std::vector<std::vector<std::uint32_t>> split(
  const std::vector<double>& places, std::size_t pieces, bool alongY)
{
  std::vector<std::uint32_t> finite;
  for (std::uint32_t i = 0; i < places.size() / 3; ++i)
    if (!std::isnan(places[3 * i]))
      finite.push_back(i);
  auto byAxis = [&](int k) {
    return [&, k](std::uint32_t a, std::uint32_t b) {
      return places[3 * a + k] < places[3 * b + k] ||
        (places[3 * a + k] == places[3 * b + k] && a < b);
    };
  };
  std::sort(finite.begin(), finite.end(), byAxis(0));
  std::vector<std::vector<std::uint32_t>> out;
  for (std::size_t s = 0; s < pieces; ++s)
  {
    std::vector<std::uint32_t> slab(finite.begin() + finite.size() * s / pieces,
      finite.begin() + finite.size() * (s + 1) / pieces);
    if (!alongY)
    {
      out.push_back(slab);
      continue;
    }
    std::sort(slab.begin(), slab.end(), byAxis(1));
    out.emplace_back(slab.begin(), slab.begin() + slab.size() / 2);
    out.emplace_back(slab.begin() + slab.size() / 2, slab.end());
  }
  return out;
}

/// A simplex of an alpha complex by its vertices' input ids and shifts from its least vertex,
/// sorted: the same for every translate, in a piece or in one process.
using Simplex = std::vector<std::array<std::int64_t, 4>>;

/// The simplices of `shape` (alphaComplex() of `placement`, of `count` points whose input ids are
/// `ids`) that `keep` accepts, each given the input ids of its vertices.
template <typename Keep>
std::vector<Simplex> simplices(const fd3::AlphaComplex& shape,
  const fd3::PeriodicPlacement& placement, std::size_t count, const std::vector<std::uint32_t>& ids,
  Keep keep)
{
  auto vertex = [&](std::uint32_t id) {
    if (id < count)
      return std::array<std::int64_t, 4>{ids[id], 0, 0, 0};
    const std::size_t k = id - count;
    return std::array<std::int64_t, 4>{ids[placement.imageSources[k]], placement.imageShifts[3 * k],
      placement.imageShifts[3 * k + 1], placement.imageShifts[3 * k + 2]};
  };
  std::vector<Simplex> out;
  auto add = [&](const std::uint32_t* v, int size) {
    Simplex simplex;
    for (int i = 0; i < size; ++i)
      simplex.push_back(vertex(v[i]));
    std::sort(simplex.begin(), simplex.end());
    for (int i = size - 1; i >= 0; --i)
      for (int k = 1; k < 4; ++k)
        simplex[i][k] -= simplex[0][k];
    if (keep(simplex))
      out.push_back(simplex);
  };
  for (const std::uint32_t t : shape.tetrahedra)
    add(&placement.tetrahedra[4 * t], 4);
  for (std::size_t k = 0; k < shape.triangles.size(); k += 3)
    add(&shape.triangles[k], 3);
  for (std::size_t k = 0; k < shape.lines.size(); k += 2)
    add(&shape.lines[k], 2);
  for (const std::uint32_t v : shape.vertices)
    add(&v, 1);
  return out;
}

/// What the pieces give, in input ids, and how many exchanges they took.
struct PieceRuns
{
  std::vector<Simplex> alphaComplex; // sorted
  std::vector<Vertices> tetrahedra;
  std::vector<double> density; // by input id
  std::vector<double> volume;  // of each input point's cell
  std::vector<std::size_t> neighbors;
  double placedVolume = 0; // of the pieces' tetrahedra, placed (placePeriodic())
  int exchanges = 0;
};

/// Runs the pieces (split()) of p in box until none asks for a wider halo; with `alpha`, each
/// piece's stars and alpha complex.
PieceRuns runPieces(
  const Points& p, const fd3::PeriodicBox& box, std::size_t pieces, bool alongY, double alpha)
{
  const std::size_t n = p.size() / 3;
  std::vector<double> places;
  EXPECT_TRUE(fd3::periodicPlaces(p.data(), n, box, places));
  const std::vector<std::vector<std::uint32_t>> own = split(places, pieces, alongY);
  fd3::Bounds extent;
  std::vector<fd3::Bounds> regions(own.size());
  std::size_t finite = 0;
  for (std::size_t r = 0; r < own.size(); ++r)
    for (const std::uint32_t i : own[r])
    {
      regions[r].include(&places[3 * i]);
      extent.include(&places[3 * i]);
      ++finite;
    }
  PieceRuns out;
  out.density.assign(n, NAN);
  out.volume.assign(n, NAN);
  out.neighbors.assign(n, 0);
  // Each piece's halo, widened where it asks, as the MPI filters' ranks widen theirs; a piece
  // that stood is not run again.
  std::vector<double> halos(own.size(), fd3::firstPeriodicHalo(box, finite, extent));
  std::vector<char> pending(own.size(), 1);
  for (; std::count(pending.begin(), pending.end(), 1) > 0; ++out.exchanges)
  {
    EXPECT_LT(out.exchanges, 20);
    for (std::size_t r = 0; r < own.size(); ++r)
    {
      if (!pending[r])
        continue;
      const double halo = halos[r];
      // The piece's points: its own, then the others' with an image in its halo.
      std::vector<std::uint32_t> ids = own[r];
      for (std::size_t s = 0; s < own.size(); ++s)
        for (const std::uint32_t i : own[s])
          if (s != r && fd3::periodicImageWithin(&places[3 * i], box, regions[r], halo))
            ids.push_back(i);
      Points xyz;
      for (const std::uint32_t i : ids)
        xyz.insert(xyz.end(), &p[3 * i], &p[3 * i] + 3);
      fd3::PeriodicPiece piece;
      piece.own = own[r].size();
      piece.ids = ids.data();
      piece.region = regions[r];
      piece.halo = halo;
      piece.points = finite;
      piece.extent = extent;
      piece.stars = alpha > 0;
      fd3::PeriodicPieceTriangulation t =
        fd3::triangulatePeriodicPiece(xyz.data(), ids.size(), box, piece, true);
      double cellsWider = 0;
      fd3::VoronoiOptions options;
      options.polyhedra = false;
      const fd3::VoronoiCells cells =
        fd3::voronoiCellsPeriodicPiece(xyz.data(), ids.size(), box, piece, cellsWider, options);
      EXPECT_EQ(t.widerHalo, cellsWider) << "the cells and the tetrahedra need the same halo";
      if (t.widerHalo > 0)
      {
        EXPECT_GT(t.widerHalo, halo);
        halos[r] = t.widerHalo;
        continue;
      }
      pending[r] = 0;
      EXPECT_EQ(t.triangulation.status, fd3::Status::Ok);
      if (alpha > 0)
      {
        // The piece's alpha complex from the stars of its points: the simplices whose least
        // vertex is one of them are its own.
        const fd3::PeriodicPlacement stars =
          fd3::placePeriodic(xyz.data(), piece.own, t.triangulation, box);
        const fd3::AlphaComplex shape = fd3::alphaComplex(xyz.data(), piece.own, stars, alpha);
        const std::vector<std::uint32_t> local(ids.begin(), ids.begin() + piece.own);
        const std::vector<Simplex> mine =
          simplices(shape, stars, piece.own, ids, [&](const Simplex& simplex) {
            return std::find(local.begin(), local.end(), simplex[0][0]) != local.end();
          });
        out.alphaComplex.insert(out.alphaComplex.end(), mine.begin(), mine.end());
        // The tetrahedra it owns, for the comparisons below.
        EXPECT_EQ(t.owned.size(), t.triangulation.numberOfTetrahedra());
        std::size_t kept = 0;
        for (std::size_t c = 0; c < t.owned.size(); ++c)
          if (t.owned[c])
          {
            std::copy_n(
              &t.triangulation.tetrahedra[4 * c], 4, &t.triangulation.tetrahedra[4 * kept]);
            std::copy_n(&t.triangulation.offsets[12 * c], 12, &t.triangulation.offsets[12 * kept]);
            ++kept;
          }
        t.triangulation.tetrahedra.resize(4 * kept);
        t.triangulation.offsets.resize(12 * kept);
        EXPECT_EQ(t.triangulation.stats.tetrahedra, kept);
      }
      const std::vector<Vertices> mine = sortedTetrahedra(t.triangulation, ids);
      out.placedVolume += placedVolume(xyz, piece.own, t.triangulation, box);
      out.tetrahedra.insert(out.tetrahedra.end(), mine.begin(), mine.end());
      for (std::size_t i = 0; i < piece.own; ++i)
        out.density[ids[i]] = t.density[i];
      for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
      {
        EXPECT_LT(cells.generators[c], piece.own) << "a cell of a ghost";
        out.volume[ids[cells.generators[c]]] = cells.volumes[c];
        out.neighbors[ids[cells.generators[c]]] = cells.numberOfNeighbors(c);
      }
    }
  }
  std::sort(out.tetrahedra.begin(), out.tetrahedra.end());
  std::sort(out.alphaComplex.begin(), out.alphaComplex.end());
  return out;
}

/// Whether the pieces give what one process gives: the same periodic tetrahedra, each once, and
/// the same densities and cells, up to the order of their sums. Returns the exchanges taken.
int expectOneProcessResult(const Points& p, const fd3::PeriodicBox& box, std::size_t pieces,
  bool alongY = false, double alpha = 0)
{
  const std::size_t n = p.size() / 3;
  const fd3::PeriodicTriangulation whole = fd3::triangulatePeriodic(p.data(), n, box);
  EXPECT_EQ(whole.status, fd3::Status::Ok);
  std::vector<std::uint32_t> identity(n);
  std::iota(identity.begin(), identity.end(), 0u);
  const fd3::PeriodicPlacement placement = fd3::placePeriodic(p.data(), n, whole, box);
  const std::vector<double> density = fd3::densities(p.data(), n, whole, placement);
  fd3::VoronoiOptions options;
  options.polyhedra = false;
  const fd3::VoronoiCells cells = fd3::voronoiCellsPeriodic(p.data(), n, box, options);

  const PieceRuns runs = runPieces(p, box, pieces, alongY, alpha);
  if (alpha > 0)
  {
    std::vector<Simplex> shape = simplices(fd3::alphaComplex(p.data(), n, placement, alpha),
      placement, n, identity, [](const Simplex&) { return true; });
    std::sort(shape.begin(), shape.end());
    EXPECT_GT(shape.size(), n / 2);
    EXPECT_EQ(runs.alphaComplex.size(), shape.size());
    EXPECT_TRUE(runs.alphaComplex == shape) << "the pieces' alpha complex is not the whole set's";
  }
  const std::vector<Vertices> expected = sortedTetrahedra(whole, identity);
  EXPECT_EQ(runs.tetrahedra.size(), expected.size());
  EXPECT_TRUE(runs.tetrahedra == expected) << "the pieces' tetrahedra are not the whole set's";
  if (box.periodic[0] && box.periodic[1] && box.periodic[2])
  {
    const double period =
      (box.hi[0] - box.lo[0]) * (box.hi[1] - box.lo[1]) * (box.hi[2] - box.lo[2]);
    EXPECT_NEAR(runs.placedVolume, period, 1e-9 * period) << "the placed tetrahedra tile a period";
  }
  for (std::size_t i = 0; i < n; ++i)
    if (whole.representative[i] == i)
      EXPECT_NEAR(runs.density[i], density[i], 1e-12 * density[i]) << "point " << i;
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
  {
    const std::uint32_t g = cells.generators[c];
    EXPECT_NEAR(runs.volume[g], cells.volumes[c], 1e-12 * cells.volumes[c]) << "cell of " << g;
    EXPECT_EQ(runs.neighbors[g], cells.numberOfNeighbors(c)) << "cell of " << g;
  }
  return runs.exchanges;
}
} // namespace

TEST(PeriodicPieces, UniformPointsNeedOneExchange)
{
  Points p = fd3test::uniformCube(3000, 21);
  for (std::size_t i = 0; i < p.size(); i += 51)
    p[i] += 1; // a period outside the box
  EXPECT_EQ(expectOneProcessResult(p, fd3::PeriodicBox(), 2, true), 1);
  EXPECT_EQ(expectOneProcessResult(p, fd3::PeriodicBox(), 3), 1);
}

TEST(PeriodicPieces, LatticeWithTiesAcrossTheFaces)
{
  Points p;
  for (int x = 0; x < 6; ++x)
    for (int y = 0; y < 6; ++y)
      for (int z = 0; z < 6; ++z)
        p.insert(p.end(), {x / 6.0, y / 6.0, z / 6.0});
  expectOneProcessResult(p, fd3::PeriodicBox(), 2, true);
}

TEST(PeriodicPieces, AHandfulOfPoints)
{
  fd3::PeriodicBox box;
  for (int k = 0; k < 3; ++k)
    box.hi[k] = 10;
  for (std::size_t n : {2, 7})
    expectOneProcessResult(fd3test::scaled(fd3test::uniformCube(n, 9), 10), box, 2);
}

TEST(PeriodicPieces, AClusterInAnEmptyBoxWidensTheHalo)
{
  // The first halo is a few spacings of the points spread over the box: the cluster's points
  // are far closer, and the tetrahedra across the empty box far wider.
  const Points p = fd3test::scaled(fd3test::uniformCube(500, 12), 0.2, 0.3);
  EXPECT_GT(expectOneProcessResult(p, fd3::PeriodicBox(), 3), 1);
}

TEST(PeriodicPieces, SlabAndClusters)
{
  fd3::PeriodicBox slab;
  slab.periodic[2] = false;
  expectOneProcessResult(fd3test::uniformCube(1500, 4), slab, 2, true);
  const Points clusters = fd3test::generate("clusters", 2000, 5);
  fd3::PeriodicBox box;
  fd3::Bounds bounds;
  for (std::size_t i = 0; i < clusters.size(); i += 3)
    bounds.include(&clusters[i]);
  for (int k = 0; k < 3; ++k)
  {
    box.lo[k] = bounds.lo[k];
    box.hi[k] = bounds.hi[k] + 0.01;
  }
  expectOneProcessResult(clusters, box, 2, true);
}

TEST(PeriodicPieces, RepeatsStayWithOnePiece)
{
  Points p = fd3test::uniformCube(400, 8);
  std::copy_n(std::array<double, 3>{0.75, 0.5, 0.25}.begin(), 3, p.begin());
  p.insert(p.end(), {1.75, 0.5, -0.75});    // point 0 a period away on two axes (exact)
  p.insert(p.end(), {p[30], p[31], p[32]}); // point 10 again
  EXPECT_EQ(expectOneProcessResult(p, fd3::PeriodicBox(), 3), 1);
}

TEST(PeriodicPieces, PointsWithinARounding)
{
  // Point 0 moved a period and back in doubles: a unit in the last place away from itself. The
  // tetrahedra at the two are flat in floats, whose spheres the certificate bounds by half a
  // period: the halo widens until it holds them.
  Points p = fd3test::uniformCube(400, 8);
  p.insert(p.end(), {p[0] + 1, p[1], p[2] - 1});
  expectOneProcessResult(p, fd3::PeriodicBox(), 3);
}

TEST(PeriodicPieces, APlaneAndOnePointAbove)
{
  // A slab's points on one plane but one: the pieces away from that point see only the plane
  // within their first halo, and must widen it to find the tetrahedra up to the point.
  fd3::PeriodicBox slab;
  slab.periodic[2] = false;
  Points p = fd3test::uniformCube(4000, 14);
  for (std::size_t i = 2; i < p.size(); i += 3)
    p[i] = 0;
  p.insert(p.end(), {0.5, 0.5, 0.3});
  EXPECT_GT(expectOneProcessResult(p, slab, 3), 1);
}

TEST(PeriodicPieces, AlphaComplexFromTheStars)
{
  // Each piece lists the simplices whose least vertex is one of its points, from the stars of its
  // points: together the whole set's complex, each simplex once.
  Points p = fd3test::uniformCube(1500, 31);
  for (std::size_t i = 1; i < p.size(); i += 51)
    p[i] += 1; // a period outside the box
  for (const double alpha : {0.06, 0.1, 1.0})
    expectOneProcessResult(p, fd3::PeriodicBox(), 2, true, alpha);
  fd3::PeriodicBox slab;
  slab.periodic[2] = false;
  expectOneProcessResult(fd3test::uniformCube(800, 4), slab, 3, false, 0.1);
  fd3::PeriodicBox four;
  for (int k = 0; k < 3; ++k)
    four.hi[k] = 4;
  Points q = fd3test::scaled(fd3test::uniformCube(3000, 11), 4);
  for (std::size_t i = 1; i < q.size(); i += 51)
    q[i] += 4;
  for (std::size_t pieces : {2, 3})
    expectOneProcessResult(q, four, pieces, false, 0.25);
}
