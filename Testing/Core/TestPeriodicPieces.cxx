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

/// What the pieces give, in input ids, and how many exchanges they took.
struct PieceRuns
{
  std::vector<Vertices> tetrahedra;
  std::vector<double> density; // by input id
  std::vector<double> volume;  // of each input point's cell
  std::vector<std::size_t> neighbors;
  double placedVolume = 0; // of the pieces' tetrahedra, placed (placePeriodic())
  int exchanges = 0;
};

/// Runs the pieces (split()) of p in box until no piece asks for a wider halo.
PieceRuns runPieces(const Points& p, const fd3::PeriodicBox& box, std::size_t pieces, bool alongY)
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
  double halo = fd3::firstPeriodicHalo(box, finite, extent);
  for (bool again = true; again; ++out.exchanges)
  {
    EXPECT_LT(out.exchanges, 20);
    again = false;
    double wider = 0;
    out.tetrahedra.clear();
    out.placedVolume = 0;
    for (std::size_t r = 0; r < own.size(); ++r)
    {
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
      const fd3::PeriodicPieceTriangulation t =
        fd3::triangulatePeriodicPiece(xyz.data(), ids.size(), box, piece, true);
      double cellsWider = 0;
      fd3::VoronoiOptions options;
      options.polyhedra = false;
      const fd3::VoronoiCells cells =
        fd3::voronoiCellsPeriodicPiece(xyz.data(), ids.size(), box, piece, cellsWider, options);
      EXPECT_EQ(t.widerHalo, cellsWider) << "the cells and the tetrahedra need the same halo";
      wider = std::max(wider, t.widerHalo);
      if (t.widerHalo > 0)
        continue;
      EXPECT_EQ(t.triangulation.status, fd3::Status::Ok);
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
    if (wider > 0)
    {
      EXPECT_GT(wider, halo);
      halo = wider;
      again = true;
    }
  }
  std::sort(out.tetrahedra.begin(), out.tetrahedra.end());
  return out;
}

/// Whether the pieces give what one process gives: the same periodic tetrahedra, each once, and
/// the same densities and cells, up to the order of their sums. Returns the exchanges taken.
int expectOneProcessResult(
  const Points& p, const fd3::PeriodicBox& box, std::size_t pieces, bool alongY = false)
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

  const PieceRuns runs = runPieces(p, box, pieces, alongY);
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
