// Weighted points: the power test against rationals, and the regular tetrahedralization checked
// by the independent exact validator (locally regular faces, hidden points truly hidden).
#include "CoreTestUtilities.h"
#include "ExactValidator.h"
#include "PointSets.h"
#include "exact/Predicates.h"
#include "fd3/Delaunay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <vector>

namespace
{
using fd3test::Points;
using fd3test::randomWeights;

/// The regular tetrahedralization of p with weights w, checked by the validator and by its own
/// figures: every finite point a vertex, hidden, or an equal-weight copy.
fd3::Triangulation triangulateWeighted(const Points& p, const std::vector<double>& w,
  const fd3::Options& options = {}, const std::string& what = "")
{
  const std::size_t n = p.size() / 3;
  fd3::Triangulation result = fd3::triangulate(p.data(), w.data(), n, options);
  EXPECT_EQ(result.status, fd3::Status::Ok) << what << ": " << fd3::toString(result.status);
  fd3test::ValidityOptions check;
  check.weights = w.data();
  check.hidden = result.hidden;
  const fd3test::ValidityReport report =
    fd3test::checkTriangulation(p.data(), n, result.tetrahedra, check);
  EXPECT_TRUE(report.valid()) << what << ": " << report.summary();
  const fd3::Statistics& s = result.stats;
  EXPECT_EQ(s.insertedPoints, report.usedVertices) << what;
  EXPECT_EQ(s.hiddenPoints, result.hidden.size()) << what;
  EXPECT_EQ(s.insertedPoints + s.hiddenPoints + s.duplicatesMerged + s.nonFinitePoints, n) << what;
  for (const std::uint32_t h : result.hidden)
    EXPECT_EQ(result.representative[h], h) << what;
  return result;
}

TEST(Weighted, PowerTestMatchesRationals)
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const bool anyMagnitude : {false, true})
    for (const double weightScale : {0.0, 1e-3, 1.0, 1e200, 1e-200})
      for (int trial = 0; trial < 400; ++trial)
      {
        fd3::Predicates predicates;
        if (anyMagnitude)
          predicates.allowAnyMagnitude();
        double p[4][3], e[3], w[4];
        for (auto& q : p)
          for (double& x : q)
            x = u(random);
        if (predicates.orient3d(p[0], p[1], p[2], p[3]) < 0)
          std::swap(p[0], p[1]);
        for (double& x : w)
          x = weightScale * u(random);
        // Half the trials near a tie: e on the orthogonal sphere of the four, as nearly as
        // doubles allow; the other half anywhere.
        double we = weightScale * u(random);
        for (double& x : e)
          x = u(random);
        if (trial % 2 == 0 && weightScale < 1e100)
        {
          // The power distance of e to the orthosphere is pd = |e|^2 - we - h(e), h the affine
          // interpolant of the lifts |p|^2 - w; we += pd puts e on it.
          double lift[4];
          for (int i = 0; i < 4; ++i)
            lift[i] = p[i][0] * p[i][0] + p[i][1] * p[i][1] + p[i][2] * p[i][2] - w[i];
          const double* q[4] = {p[0], p[1], p[2], p[3]};
          double barycentric[4],
            volume = fd3test::exactOrient3d(q[0], q[1], q[2], q[3]) > 0 ? 1 : 0;
          ASSERT_EQ(volume, 1);
          auto six = [](const double* a, const double* b, const double* c, const double* d) {
            const double u1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const double z[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
            return u1[0] * (v[1] * z[2] - v[2] * z[1]) - u1[1] * (v[0] * z[2] - v[2] * z[0]) +
              u1[2] * (v[0] * z[1] - v[1] * z[0]);
          };
          const double total = six(p[0], p[1], p[2], p[3]);
          double h = 0;
          for (int i = 0; i < 4; ++i)
          {
            const double* r[4] = {p[0], p[1], p[2], p[3]};
            r[i] = e;
            barycentric[i] = six(r[0], r[1], r[2], r[3]) / total;
            h += barycentric[i] * lift[i];
          }
          we = e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - h;
        }
        const double* q[4] = {p[0], p[1], p[2], p[3]};
        EXPECT_EQ(predicates.powerTest(q, e, w, we), fd3test::exactPowerTest(q, e, w, we))
          << "weights ~" << weightScale << (anyMagnitude ? ", any magnitude" : "");
      }
}

TEST(Weighted, EqualWeightsPowerTestIsInSphere)
{
  const Points lattice = fd3test::lattice(3); // cospherical quadruples by the dozen
  fd3::Predicates predicates;
  const double w[4] = {0.5, 0.5, 0.5, 0.5};
  std::size_t ties = 0;
  for (std::size_t a = 0; a + 4 < lattice.size() / 3; a += 3)
  {
    const double* q[4] = {&lattice[3 * a], &lattice[3 * a + 3], &lattice[3 * a + 9],
      &lattice[3 * a + 27 < lattice.size() ? 3 * a + 27 : 0]};
    if (predicates.orient3d(q[0], q[1], q[2], q[3]) <= 0)
      continue;
    for (std::size_t e = 0; e < lattice.size() / 3; ++e)
    {
      const int s = predicates.powerTest(q, &lattice[3 * e], w, 0.5);
      EXPECT_EQ(s, predicates.inSphere(q[0], q[1], q[2], q[3], &lattice[3 * e]));
      EXPECT_EQ(predicates.powerTestSoS(q, &lattice[3 * e], w, 0.5),
        predicates.inSphereSoS(q, &lattice[3 * e]));
      ties += s == 0;
    }
  }
  EXPECT_GT(ties, 0u);
}

TEST(Weighted, UniformPointsWithRandomRadiiAreRegular)
{
  for (const int threads : {1, 3})
  {
    const Points p = fd3test::uniformCube(4000, 11);
    const std::vector<double> w = randomWeights(4000, 0.001, 0.08, 12);
    fd3::Options options;
    options.threads = threads;
    const fd3::Triangulation t = triangulateWeighted(p, w, options, "uniform");
    EXPECT_GT(t.hidden.size(), 10u); // balls this large hide some centres
  }
}

TEST(Weighted, EqualWeightsGiveTheDelaunayTetrahedraBitForBit)
{
  const Points p = fd3test::uniformBall(3000, 5);
  const std::vector<double> w(3000, 0.37);
  const fd3::Triangulation weighted = fd3::triangulate(p.data(), w.data(), 3000);
  const fd3::Triangulation plain = fd3::triangulate(p.data(), 3000);
  ASSERT_EQ(weighted.status, fd3::Status::Ok);
  EXPECT_TRUE(weighted.tetrahedra == plain.tetrahedra);
  EXPECT_TRUE(weighted.neighbors == plain.neighbors);
  EXPECT_TRUE(weighted.hidden.empty());
}

/// Radii of the lattice's points: 0.5 and 0 alternating, as a rock-salt crystal's two ions.
std::vector<double> alternatingRadii(const Points& p)
{
  std::vector<double> radii(p.size() / 3);
  for (std::size_t i = 0; i < radii.size(); ++i)
    radii[i] = static_cast<long>(p[3 * i] + p[3 * i + 1] + p[3 * i + 2]) % 2 ? 0.5 : 0.0;
  return radii;
}

/// Uniform balls of radius 0.1 and, a quarter of the points, balls of 0.001 deep inside them.
Points packing(std::vector<double>& radii)
{
  const std::size_t large = 3000, small = 1000;
  Points p = fd3test::uniformCube(large, 21);
  radii.assign(large, 0.1);
  std::mt19937_64 random(22);
  std::uniform_real_distribution<double> offset(-0.005, 0.005);
  std::uniform_int_distribution<std::size_t> pick(0, large - 1);
  for (std::size_t i = 0; i < small; ++i)
  {
    const std::size_t c = pick(random);
    for (int k = 0; k < 3; ++k)
      p.push_back(p[3 * c + k] + offset(random));
    radii.push_back(0.001);
  }
  return p;
}

std::vector<double> squares(const std::vector<double>& radii)
{
  std::vector<double> w(radii.size());
  for (std::size_t i = 0; i < w.size(); ++i)
    w[i] = radii[i] * radii[i];
  return w;
}

TEST(Weighted, LatticeWithEqualAndAlternatingWeights)
{
  const Points p = fd3test::lattice(6);
  const std::size_t n = p.size() / 3;
  std::vector<double> equal(n, 0.1);
  const std::vector<double> alternating = squares(alternatingRadii(p));
  triangulateWeighted(p, equal, {}, "lattice, equal weights");
  const fd3::Triangulation t = triangulateWeighted(p, alternating, {}, "lattice, alternating");
  EXPECT_GT(t.stats.symbolicTies, 0u);
}

// Small balls deep inside large ones: a quarter of the points, nearly all of them hidden.
TEST(Weighted, PackingWithAQuarterHidden)
{
  std::vector<double> radii;
  const Points p = packing(radii);
  const fd3::Triangulation t = triangulateWeighted(p, squares(radii), {}, "packing");
  EXPECT_GE(t.hidden.size(), 900u); // of the 1000 small balls
}

// Inserted in input order, a heavy point last takes vertices out of the mesh.
TEST(Weighted, HeavyPointHidesEarlierVertices)
{
  Points p = fd3test::uniformCube(200, 31);
  std::vector<double> w(200, 0.0);
  p.insert(p.end(), {0.5, 0.5, 0.5});
  w.push_back(0.3 * 0.3);
  fd3::Options options;
  options.order = fd3::InsertionOrder::Input;
  const fd3::Triangulation t = triangulateWeighted(p, w, options, "heavy last");
  EXPECT_GT(t.hidden.size(), 5u);
  EXPECT_FALSE(std::binary_search(t.hidden.begin(), t.hidden.end(), 200u));
}

TEST(Weighted, CopiesAtOnePositionKeepTheHeaviest)
{
  Points p = fd3test::uniformCube(100, 41);
  std::vector<double> w = randomWeights(100, 0.0, 0.01, 42);
  // Point 7 repeated twice lighter and once heavier, point 8 once with its own weight.
  for (const double factor : {0.5, 0.25, 2.0})
  {
    p.insert(p.end(), {p[21], p[22], p[23]});
    w.push_back(w[7] * factor);
  }
  p.insert(p.end(), {p[24], p[25], p[26]});
  w.push_back(w[8]);
  const fd3::Triangulation t = triangulateWeighted(p, w, {}, "copies");
  EXPECT_TRUE(std::binary_search(t.hidden.begin(), t.hidden.end(), 7u));
  EXPECT_TRUE(std::binary_search(t.hidden.begin(), t.hidden.end(), 100u));
  EXPECT_TRUE(std::binary_search(t.hidden.begin(), t.hidden.end(), 101u));
  EXPECT_EQ(t.representative[103], 8u);
  EXPECT_EQ(t.stats.duplicatesMerged, 1u);
}

TEST(Weighted, NonFiniteWeightsAreLeftOut)
{
  Points p = fd3test::uniformCube(300, 51);
  std::vector<double> w = randomWeights(300, 0.0, 0.02, 52);
  w[3] = NAN;
  w[4] = INFINITY;
  const fd3::Triangulation t = triangulateWeighted(p, w, {}, "non-finite weights");
  EXPECT_EQ(t.stats.nonFinitePoints, 2u);
  EXPECT_EQ(t.representative[3], fd3::kNoPoint);
}

// Weights far from the squared coordinates' magnitudes leave the scaled frame for exact integers.
TEST(Weighted, WeightsOfAnyMagnitude)
{
  const Points p = fd3test::uniformCube(500, 61);
  for (const double scale : {1e-300, 1e-30, 1e30, 1e300})
  {
    std::vector<double> w = randomWeights(500, 0.0, 0.05, 62);
    for (std::size_t i = 0; i < w.size(); i += 50)
      w[i] *= scale;
    triangulateWeighted(p, w, {}, "weights scaled by " + std::to_string(scale));
  }
  triangulateWeighted(
    fd3test::scaled(p, 1e-150), randomWeights(500, 0.0, 1e-151, 63), {}, "tiny coordinates");
}
} // namespace

namespace
{
/// The complex's simplices as sorted id lists, for comparing two complexes.
std::vector<std::vector<std::uint32_t>> simplicesOf(
  const fd3::AlphaComplex& complex, const fd3::Triangulation& t)
{
  std::vector<std::vector<std::uint32_t>> all;
  auto add = [&](const std::uint32_t* ids, int n) {
    std::vector<std::uint32_t> s(ids, ids + n);
    std::sort(s.begin(), s.end());
    all.push_back(s);
  };
  for (const std::uint32_t tet : complex.tetrahedra)
    add(&t.tetrahedra[4 * std::size_t(tet)], 4);
  for (std::size_t i = 0; i < complex.triangles.size(); i += 3)
    add(&complex.triangles[i], 3);
  for (std::size_t i = 0; i < complex.lines.size(); i += 2)
    add(&complex.lines[i], 2);
  for (const std::uint32_t v : complex.vertices)
    add(&v, 1);
  std::sort(all.begin(), all.end());
  return all;
}

// Zero weights give the circumspheres, and a weight W taken from every point raises every squared
// orthoradius by W: the same complex at alpha^2 + W. Hidden points are in none of it.
TEST(Weighted, AlphaComplexOfOrthogonalSpheres)
{
  const std::size_t n = 3000;
  const Points p = fd3test::uniformCube(n, 71);
  std::vector<double> w = randomWeights(n, 0.0, 0.06, 72);
  fd3::Options options;
  options.computeNeighbors = true;
  const fd3::Triangulation t = fd3::triangulate(p.data(), w.data(), n, options);
  ASSERT_FALSE(t.hidden.empty());
  const double alpha = 0.05;
  const fd3::AlphaComplex complex = fd3::alphaComplex(p.data(), w.data(), n, t, alpha);
  EXPECT_FALSE(complex.tetrahedra.empty());
  EXPECT_LT(complex.tetrahedra.size(), t.numberOfTetrahedra());
  const auto simplices = simplicesOf(complex, t);
  for (const auto& s : simplices)
    for (const std::uint32_t id : s)
      EXPECT_FALSE(std::binary_search(t.hidden.begin(), t.hidden.end(), id));
  std::vector<double> shifted(w);
  for (double& x : shifted)
    x -= 0.25;
  const fd3::Triangulation same = fd3::triangulate(p.data(), shifted.data(), n, options);
  EXPECT_EQ(
    fd3test::canonicalTetrahedra(same.tetrahedra), fd3test::canonicalTetrahedra(t.tetrahedra));
  const auto shiftedSimplices = simplicesOf(
    fd3::alphaComplex(p.data(), shifted.data(), n, same, std::sqrt(alpha * alpha + 0.25)), same);
  std::vector<std::vector<std::uint32_t>> differ;
  std::set_symmetric_difference(simplices.begin(), simplices.end(), shiftedSimplices.begin(),
    shiftedSimplices.end(), std::back_inserter(differ));
  EXPECT_TRUE(differ.empty()) << differ.size() << " of " << simplices.size() << " differ, first "
                              << differ.front().size() << " ids";

  const fd3::Triangulation plain = fd3::triangulate(p.data(), n, options);
  const std::vector<double> zero(n, 0.0);
  EXPECT_EQ(simplicesOf(fd3::alphaComplex(p.data(), zero.data(), n, plain, alpha), plain),
    simplicesOf(fd3::alphaComplex(p.data(), n, plain, alpha), plain));
}
} // namespace

#ifdef FD3_TEST_WITH_VOROPP
#include "VoroppVolumes.h"
#endif
#include "fd3/Voronoi.h"

namespace
{
/// The power cells of p with weights w in `box`, checked for what holds on any input: a cell
/// per distinct finite point, the hidden ones empty, the volumes filling the box.
fd3::VoronoiCells powerCells(const Points& p, const std::vector<double>& w, const fd3::Bounds& box,
  int threads, const std::string& what)
{
  fd3::VoronoiOptions options;
  options.box = box;
  options.threads = threads;
  fd3::VoronoiCells cells = fd3::voronoiCells(p.data(), w.data(), w.size(), options);
  EXPECT_EQ(cells.status, fd3::Status::Ok) << what;
  const fd3::Triangulation regular = fd3::triangulate(p.data(), w.data(), w.size());
  double sum = 0;
  std::size_t empty = 0;
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
  {
    sum += cells.volumes[c];
    const bool hidden =
      std::binary_search(regular.hidden.begin(), regular.hidden.end(), cells.generators[c]);
    if (hidden)
    {
      EXPECT_EQ(cells.volumes[c], 0.0) << what;
      EXPECT_EQ(cells.numberOfFaces(c), 0u) << what;
    }
    empty += hidden;
  }
  EXPECT_EQ(empty, regular.hidden.size()) << what;
  const double volume = box.extent(0) * box.extent(1) * box.extent(2);
  EXPECT_NEAR(sum, volume, 1e-12 * volume) << what;
  return cells;
}

TEST(Weighted, PowerCellsFillTheBoxAndHiddenPointsHaveNone)
{
  const std::size_t n = 3000;
  const Points p = fd3test::uniformCube(n, 91);
  const std::vector<double> w = randomWeights(n, 0.0, 0.06, 92);
  fd3::Bounds box;
  for (int a = 0; a < 3; ++a)
  {
    box.lo[a] = 0.1;
    box.hi[a] = 0.9;
  }
  const fd3::VoronoiCells one = powerCells(p, w, box, 1, "one thread");
  const fd3::VoronoiCells three = powerCells(p, w, box, 3, "three threads");
  EXPECT_TRUE(one.volumes == three.volumes);
  EXPECT_TRUE(one.points == three.points);
  // Zero weights give the Voronoi cells.
  const std::vector<double> zero(n, 0.0);
  fd3::VoronoiOptions options;
  options.box = box;
  EXPECT_TRUE(fd3::voronoiCells(p.data(), zero.data(), n, options).volumes ==
    fd3::voronoiCells(p.data(), n, options).volumes);
}

#ifdef FD3_TEST_WITH_VOROPP
/// Voro++'s radical (container_poly) cell volumes by input id, -1 where it makes none.
std::vector<double> voroppRadicalVolumes(
  const Points& p, const std::vector<double>& radii, const fd3::Bounds& b)
{
  const std::size_t n = radii.size();
  const int blocks = fd3test::voroppBlocks(n);
  voro::container_poly box(b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2], b.hi[2], blocks, blocks,
    blocks, false, false, false, 8);
  for (std::size_t i = 0; i < n; ++i)
    box.put(int(i), p[3 * i], p[3 * i + 1], p[3 * i + 2], radii[i]);
  return fd3test::voroppVolumes(box, n);
}

// Voro++ clips to its container, our cells to the box: the same box, points strictly inside.
void expectVoroppVolumes(const Points& p, const std::vector<double>& radii, const std::string& what)
{
  fd3::Bounds box = fd3::finiteBounds(p.data(), radii.size());
  for (int a = 0; a < 3; ++a)
  {
    const double margin = 0.01 * box.extent(a);
    box.lo[a] -= margin;
    box.hi[a] += margin;
  }
  const fd3::VoronoiCells cells = powerCells(p, squares(radii), box, 2, what);
  const std::vector<double> reference = voroppRadicalVolumes(p, radii, box);
  std::size_t compared = 0;
  for (std::size_t c = 0; c < cells.numberOfCells(); ++c)
  {
    const double expected = std::max(0.0, reference[cells.generators[c]]);
    EXPECT_NEAR(cells.volumes[c], expected, 1e-9 * std::max(expected, 1e-12 * box.extent(0)))
      << what << " point " << cells.generators[c];
    compared += expected > 0;
  }
  EXPECT_GT(compared, radii.size() / 2) << what;
}

TEST(Weighted, PowerCellsAgainstVoroppRadicalCells)
{
  const Points p = fd3test::uniformCube(4000, 93);
  std::vector<double> radii(4000);
  std::mt19937_64 random(94);
  std::uniform_real_distribution<double> radius(0.001, 0.05);
  for (double& r : radii)
    r = radius(random);
  expectVoroppVolumes(p, radii, "uniform");
  std::vector<double> atomRadii;
  const Points atoms = fd3test::molecule(2000, 95, atomRadii);
  expectVoroppVolumes(atoms, atomRadii, "molecule");
  // Exact ties: the cells are unique where the tetrahedra are not.
  const Points lattice = fd3test::lattice(6);
  expectVoroppVolumes(lattice, std::vector<double>(lattice.size() / 3, 0.3), "lattice, equal");
  expectVoroppVolumes(lattice, alternatingRadii(lattice), "lattice, alternating");
  std::vector<double> packingRadii;
  const Points balls = packing(packingRadii);
  expectVoroppVolumes(balls, packingRadii, "packing");
}
#endif
} // namespace

namespace
{
// A weighted mesh built in pieces (add() with weights, as the power cells add their far points)
// has the tetrahedra and hidden points of the whole set at once; copies of a vertex that come
// later hide it or are hidden by their weight.
TEST(Weighted, MeshBuiltInPiecesIsTheWholeSets)
{
  const std::size_t n = 4000, first = 2500;
  Points p = fd3test::uniformCube(n, 101);
  std::vector<double> w = randomWeights(n, 0.0, 0.06, 102);
  // Later copies of two early points: one heavier, one lighter.
  p.insert(p.end(), {p[30], p[31], p[32], p[33], p[34], p[35]});
  w.push_back(w[10] + 0.01);
  w.push_back(w[11] / 2);
  const std::size_t total = w.size();
  const fd3::Frame frame = fd3::frameOf(p.data(), total);
  fd3::IncrementalDelaunay mesh(p.data(), first, {}, frame, total - first, w.data());
  EXPECT_THROW(mesh.add(p.data() + 3 * first, 1), std::logic_error);
  fd3::MeshChange change;
  EXPECT_THROW(mesh.addOne(p.data(), change), std::logic_error);
  mesh.add(p.data() + 3 * first, total - first, w.data() + first);
  const fd3::Triangulation pieces = mesh.release();
  const fd3::Triangulation whole = fd3::triangulate(p.data(), w.data(), total);
  ASSERT_EQ(pieces.status, fd3::Status::Ok);
  EXPECT_EQ(fd3test::canonicalTetrahedra(pieces.tetrahedra),
    fd3test::canonicalTetrahedra(whole.tetrahedra));
  EXPECT_EQ(pieces.hidden, whole.hidden);
  EXPECT_TRUE(std::binary_search(pieces.hidden.begin(), pieces.hidden.end(), 10u));
  EXPECT_TRUE(std::binary_search(pieces.hidden.begin(), pieces.hidden.end(), total - 1));

  const std::vector<double> plain(p.begin(), p.begin() + 3 * first);
  fd3::IncrementalDelaunay unweighted(plain.data(), first, {}, frame);
  EXPECT_THROW(unweighted.add(p.data() + 3 * first, 1, w.data()), std::logic_error);
}
// A distributed piece's weighted mesh, its own points first and the received ones (with their
// weights) added, gives the power cells that its points give from scratch: the far points take
// the least weight, of every point it was given, and no cell in the box changes.
TEST(Weighted, PowerCellsOfAMeshAreThoseOfItsPoints)
{
  const std::size_t n = 3000, own = 1800;
  const Points p = fd3test::uniformCube(n, 61);
  std::vector<double> w = randomWeights(n, 0.0, 0.05, 62);
  w[5] = 0.3 * 0.3; // a heavy point hides its neighbours
  const fd3::Bounds bounds = fd3::finiteBounds(p.data(), n);
  for (const fd3::Bounds& box : {bounds, fd3test::boxOf({0.1, 0.9, 0.2, 0.8, 0.0, 1.0})})
  {
    fd3::VoronoiOptions options;
    options.generators = own;
    options.box = box;
    const fd3::VoronoiCells scratch = fd3::voronoiCells(p.data(), w.data(), n, options);
    std::vector<double> withFar = p;
    const std::vector<double> far = fd3::voronoiFarPoints(bounds, box);
    withFar.insert(withFar.end(), far.begin(), far.end());
    fd3::Options meshOptions;
    meshOptions.computeNeighbors = false;
    fd3::IncrementalDelaunay mesh(fd3::Coordinates(p.begin(), p.begin() + 3 * own), meshOptions,
      fd3test::frameOf(withFar), n - own, w.data());
    mesh.add(p.data() + 3 * own, n - own, w.data() + own);
    fd3::Coordinates back;
    const fd3::VoronoiCells fromMesh = fd3::voronoiCells(mesh, bounds, options, back, w.data());
    ASSERT_EQ(fromMesh.status, fd3::Status::Ok);
    ASSERT_EQ(fromMesh.generators, scratch.generators);
    std::size_t empty = 0;
    double sum = 0;
    for (std::size_t c = 0; c < scratch.numberOfCells(); ++c)
    {
      EXPECT_NEAR(fromMesh.volumes[c], scratch.volumes[c], 1e-12) << "cell " << c;
      EXPECT_EQ(fromMesh.numberOfNeighbors(c), scratch.numberOfNeighbors(c)) << "cell " << c;
      empty += scratch.volumes[c] == 0;
      sum += fromMesh.volumes[c];
    }
    EXPECT_GT(empty, 0u); // the heavy point's hidden neighbours
    EXPECT_LT(sum, box.extent(0) * box.extent(1) * box.extent(2)); // the other points' cells
  }
}

} // namespace
