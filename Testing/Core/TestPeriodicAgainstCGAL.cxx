// CGAL's Periodic_3_Delaunay_triangulation_3 (a test-only peer), in the unit cube, against the
// periodic validator and against Core. The validator passes it and, for slabs, the Delaunay
// tetrahedralization of copies of points on a binary grid (whose translates are exact doubles)
// cut to one period, and each kind of damage fails it. Core's periodic tetrahedra are CGAL's on
// generic input, where the tetrahedralization is unique.
#include "PeriodicTestUtilities.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"
#include "fd3/Periodic.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Periodic_3_Delaunay_triangulation_3.h>
#include <CGAL/Periodic_3_Delaunay_triangulation_traits_3.h>
#include <CGAL/Periodic_3_regular_triangulation_3.h>
#include <CGAL/Periodic_3_regular_triangulation_traits_3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace
{
using fd3test::PeriodicDomain;
using fd3test::PeriodicTetrahedron;
using fd3test::Points;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Traits = CGAL::Periodic_3_Delaunay_triangulation_traits_3<Kernel>;
using Periodic = CGAL::Periodic_3_Delaunay_triangulation_3<Traits>;
using RegularTraits = CGAL::Periodic_3_regular_triangulation_traits_3<Kernel>;
using PeriodicRegular = CGAL::Periodic_3_regular_triangulation_3<RegularTraits>;
using Tetrahedra = std::vector<PeriodicTetrahedron>;

/// CGAL's periodic tetrahedra of points in [0, 1)^3, each once.
Tetrahedra cgalPeriodic(const Points& p)
{
  std::map<std::array<double, 3>, std::uint32_t> ids;
  std::vector<Periodic::Point> points;
  for (std::size_t i = 0; i < p.size() / 3; ++i)
  {
    ids.emplace(std::array<double, 3>{p[3 * i], p[3 * i + 1], p[3 * i + 2]}, std::uint32_t(i));
    points.emplace_back(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  }
  Periodic periodic(points.begin(), points.end(), Periodic::Iso_cuboid(0, 0, 0, 1, 1, 1));
  Tetrahedra out;
  for (auto it = periodic.periodic_tetrahedra_begin(Periodic::UNIQUE);
       it != periodic.periodic_tetrahedra_end(Periodic::UNIQUE); ++it)
  {
    PeriodicTetrahedron t;
    for (int i = 0; i < 4; ++i)
    {
      const Periodic::Point& q = (*it)[i].first;
      t.ids[i] = ids.at({q.x(), q.y(), q.z()});
      for (int k = 0; k < 3; ++k)
        t.offsets[i][k] = (*it)[i].second[k];
    }
    out.push_back(t);
  }
  return out;
}

/// CGAL's periodic regular tetrahedra of weighted points in [0, 1)^3, each once, and its count of
/// hidden points.
Tetrahedra cgalPeriodicRegular(const Points& p, const std::vector<double>& w, std::size_t& hidden)
{
  std::map<std::array<double, 3>, std::uint32_t> ids;
  std::vector<PeriodicRegular::Weighted_point> points;
  for (std::size_t i = 0; i < p.size() / 3; ++i)
  {
    ids.emplace(std::array<double, 3>{p[3 * i], p[3 * i + 1], p[3 * i + 2]}, std::uint32_t(i));
    points.emplace_back(PeriodicRegular::Bare_point(p[3 * i], p[3 * i + 1], p[3 * i + 2]), w[i]);
  }
  PeriodicRegular regular(PeriodicRegular::Iso_cuboid(0, 0, 0, 1, 1, 1));
  regular.insert(points.begin(), points.end());
  hidden = regular.number_of_hidden_points();
  Tetrahedra out;
  for (auto it = regular.periodic_tetrahedra_begin(PeriodicRegular::UNIQUE);
       it != regular.periodic_tetrahedra_end(PeriodicRegular::UNIQUE); ++it)
  {
    PeriodicTetrahedron t;
    for (int i = 0; i < 4; ++i)
    {
      const auto& q = (*it)[i].first.point();
      t.ids[i] = ids.at({q.x(), q.y(), q.z()});
      for (int k = 0; k < 3; ++k)
        t.offsets[i][k] = (*it)[i].second[k];
    }
    out.push_back(t);
  }
  return out;
}

/// n points on the grid of 2^-20 in [0, 1)^3: every translate by whole periods is a double.
Points gridPoints(std::size_t n, std::uint64_t seed)
{
  std::mt19937_64 random(seed);
  Points p(3 * n);
  for (double& x : p)
    x = std::ldexp(double(random() >> 44), -20);
  return p;
}

/// The periodic tetrahedra of grid points in the unit box, periodic along `periodic`: the
/// Delaunay tetrahedralization of the points and their copies up to two periods away along those
/// axes, cut to the tetrahedra whose least vertex (least id, then least offset) is an original
/// point. Enough copies for well-spread points (the tetrahedra under a slab's hull, whose spheres
/// are a period wide, need the second ring), which is all the validator needs of it.
Tetrahedra delaunayOfCopies(const Points& p, const bool periodic[3])
{
  const std::size_t n = p.size() / 3;
  std::vector<std::array<std::int32_t, 3>> shifts;
  for (int x = -2; x <= 2; ++x)
    for (int y = -2; y <= 2; ++y)
      for (int z = -2; z <= 2; ++z)
        if ((periodic[0] || x == 0) && (periodic[1] || y == 0) && (periodic[2] || z == 0))
          shifts.push_back({x, y, z});
  Points copies;
  for (const auto& s : shifts)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k)
        copies.push_back(p[3 * i + k] + s[k]);
  const fd3::Triangulation t = fd3::triangulate(copies.data(), copies.size() / 3, fd3::Options());
  EXPECT_EQ(t.status, fd3::Status::Ok);
  Tetrahedra out;
  for (std::size_t c = 0; c < t.tetrahedra.size() / 4; ++c)
  {
    PeriodicTetrahedron tet;
    std::array<std::int64_t, 4> least = {INT64_MAX, 0, 0, 0};
    for (int i = 0; i < 4; ++i)
    {
      const std::uint32_t v = t.tetrahedra[4 * c + i];
      tet.ids[i] = v % n;
      tet.offsets[i] = shifts[v / n];
      least =
        std::min(least, {tet.ids[i], tet.offsets[i][0], tet.offsets[i][1], tet.offsets[i][2]});
    }
    if (least[1] == 0 && least[2] == 0 && least[3] == 0)
      out.push_back(tet);
  }
  return out;
}

std::string summary(const fd3test::ValidityReport& report)
{
  return report.summary();
}

TEST(PeriodicValidator, AcceptsCGALOnUniformPoints)
{
  const Points p = fd3test::uniformCube(400, 7);
  const Tetrahedra tets = cgalPeriodic(p);
  const auto report = fd3test::checkPeriodicTriangulation(p.data(), 400, PeriodicDomain(), tets);
  EXPECT_TRUE(report.valid()) << summary(report);
  EXPECT_EQ(report.usedVertices, 400u);
  EXPECT_EQ(report.hullFaces, 0u);
  EXPECT_EQ(report.interiorFaces, 2 * tets.size());
}

TEST(PeriodicValidator, AcceptsCGALOnLatticesWithTiesAcrossTheFaces)
{
  for (int k : {4, 5, 10}) // spacings 1/4 (exact), 1/5 and 1/10 (rounded, their sums are not)
  {
    Points p;
    for (int x = 0; x < k; ++x)
      for (int y = 0; y < k; ++y)
        for (int z = 0; z < k; ++z)
          p.insert(p.end(), {x / double(k), y / double(k), z / double(k)});
    const Tetrahedra tets = cgalPeriodic(p);
    const auto report =
      fd3test::checkPeriodicTriangulation(p.data(), p.size() / 3, PeriodicDomain(), tets);
    EXPECT_TRUE(report.valid()) << k << ": " << summary(report);
    EXPECT_EQ(report.usedVertices, p.size() / 3);
  }
}

TEST(PeriodicValidator, RejectsDamage)
{
  const Points p = fd3test::uniformCube(300, 11);
  const Tetrahedra tets = cgalPeriodic(p);
  ASSERT_TRUE(fd3test::checkPeriodicTriangulation(p.data(), 300, PeriodicDomain(), tets).valid());
  auto rejects = [&](const Tetrahedra& damaged) {
    return !fd3test::checkPeriodicTriangulation(p.data(), 300, PeriodicDomain(), damaged).valid();
  };
  Tetrahedra missing(tets.begin() + 1, tets.end());
  EXPECT_TRUE(rejects(missing));
  Tetrahedra translatedTwice = tets;
  PeriodicTetrahedron copy = tets[5];
  for (auto& offset : copy.offsets)
    offset[2] += 1;
  translatedTwice.push_back(copy);
  EXPECT_TRUE(rejects(translatedTwice));
  Tetrahedra otherImage = tets;
  for (PeriodicTetrahedron& t : otherImage) // the first tetrahedron with a vertex across a face
    if (std::any_of(t.offsets.begin(), t.offsets.end(), [](const auto& o) { return o[0] != 0; }))
    {
      for (auto& offset : t.offsets)
        offset[0] = 0;
      break;
    }
  EXPECT_TRUE(rejects(otherImage));
  Tetrahedra inverted = tets;
  std::swap(inverted[3].ids[0], inverted[3].ids[1]);
  std::swap(inverted[3].offsets[0], inverted[3].offsets[1]);
  EXPECT_TRUE(rejects(inverted));
  // Points moved by whole periods are the same periodic set: the tetrahedra still hold.
  Points moved = p;
  moved[0] += 1;
  moved[4] -= 2;
  moved[8] += 3;
  EXPECT_TRUE(
    fd3test::checkPeriodicTriangulation(moved.data(), 300, PeriodicDomain(), tets).valid());
  Points notPeriodic = p;
  notPeriodic[0] += 0.5;
  EXPECT_FALSE(
    fd3test::checkPeriodicTriangulation(notPeriodic.data(), 300, PeriodicDomain(), tets).valid());
}

// A 2-3 flip of two tetrahedra inside the box leaves a triangulation that is not Delaunay.
TEST(PeriodicValidator, RejectsAFaceThatIsNotLocallyDelaunay)
{
  const Points p = fd3test::uniformCube(300, 13);
  const Tetrahedra tets = cgalPeriodic(p);
  auto at = [&](const PeriodicTetrahedron& t, int i) { return &p[3 * t.ids[i]]; };
  auto inside = [&](const PeriodicTetrahedron& t) {
    return std::all_of(t.offsets.begin(), t.offsets.end(), [](const auto& o) {
      return o == std::array<std::int32_t, 3>{0, 0, 0};
    });
  };
  bool flipped = false;
  for (std::size_t s = 0; s < tets.size() && !flipped; ++s)
    for (std::size_t u = s + 1; u < tets.size() && !flipped; ++u)
    {
      const PeriodicTetrahedron &a = tets[s], &b = tets[u];
      if (!inside(a) || !inside(b))
        continue;
      // Shared face: the three ids of a that b has; d and e the apexes.
      int d = -1, shared = 0;
      for (int i = 0; i < 4; ++i)
      {
        const bool inB = std::find(b.ids.begin(), b.ids.end(), a.ids[i]) != b.ids.end();
        shared += inB;
        if (!inB)
          d = i;
      }
      if (shared != 3)
        continue;
      int e = 0;
      while (std::find(a.ids.begin(), a.ids.end(), b.ids[e]) != a.ids.end())
        ++e;
      static constexpr int kOutward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
      const int* f = kOutward[d]; // the face, seen from outside a: apex e is beyond it
      PeriodicTetrahedron three[3] = {{{a.ids[f[0]], a.ids[f[1]], a.ids[d], b.ids[e]}, {}},
        {{a.ids[f[1]], a.ids[f[2]], a.ids[d], b.ids[e]}, {}},
        {{a.ids[f[2]], a.ids[f[0]], a.ids[d], b.ids[e]}, {}}};
      // The flip exists where the edge from d to e crosses the face: three tetrahedra of one
      // orientation.
      int signs = 0;
      for (const PeriodicTetrahedron& t : three)
        signs += fd3test::exactOrient3d(at(t, 0), at(t, 1), at(t, 2), at(t, 3));
      if (signs == -3)
        for (PeriodicTetrahedron& t : three)
          std::swap(t.ids[0], t.ids[1]);
      else if (signs != 3)
        continue;
      Tetrahedra damaged;
      for (std::size_t i = 0; i < tets.size(); ++i)
        if (i != s && i != u)
          damaged.push_back(tets[i]);
      damaged.insert(damaged.end(), three, three + 3);
      const auto report =
        fd3test::checkPeriodicTriangulation(p.data(), 300, PeriodicDomain(), damaged);
      EXPECT_FALSE(report.valid());
      EXPECT_TRUE(
        fd3test::checkPeriodicTriangulation(p.data(), 300, PeriodicDomain(), damaged, false)
          .valid())
        << summary(report);
      flipped = true;
    }
  EXPECT_TRUE(flipped);
}

TEST(PeriodicValidator, AcceptsSlabsAndColumnsAndChecksTheirHull)
{
  for (const auto& axes :
    {std::array<bool, 3>{true, true, false}, std::array<bool, 3>{false, true, true},
      std::array<bool, 3>{true, false, false}, std::array<bool, 3>{true, true, true}})
  {
    // A slab's hull is the planes of its highest and lowest points, each with its images: three
    // points on each plane, unlike one, whose images make rectangles (ties that a perturbation
    // that is not the same for every translate breaks differently in each copy).
    Points p = gridPoints(300, 17);
    const auto free = std::find(axes.begin(), axes.end(), false) - axes.begin();
    if (std::count(axes.begin(), axes.end(), false) == 1)
      for (int i = 0; i < 3; ++i)
      {
        p[3 * i + free] = 0;
        p[3 * (i + 3) + free] = 1 - 0x1p-20;
      }
    PeriodicDomain domain;
    std::copy(axes.begin(), axes.end(), domain.periodic);
    const Tetrahedra tets = delaunayOfCopies(p, domain.periodic);
    const auto report = fd3test::checkPeriodicTriangulation(p.data(), 300, domain, tets);
    EXPECT_TRUE(report.valid()) << axes[0] << axes[1] << axes[2] << ": " << summary(report);
    EXPECT_EQ(report.usedVertices, 300u);
    EXPECT_EQ(report.hullFaces > 0, !(axes[0] && axes[1] && axes[2]));
    if (axes[2])
      continue;
    // The same tetrahedra do not tile the box periodic along z too.
    PeriodicDomain closed = domain;
    closed.periodic[2] = true;
    EXPECT_FALSE(fd3test::checkPeriodicTriangulation(p.data(), 300, closed, tets).valid());
  }
}

/// A periodic tetrahedron up to translation: its (id, offset) vertices moved so that the least one
/// has offset 0, sorted.
std::array<std::array<int, 4>, 4> translated(const PeriodicTetrahedron& t)
{
  std::array<std::array<int, 4>, 4> v;
  for (int i = 0; i < 4; ++i)
    v[i] = {int(t.ids[i]), t.offsets[i][0], t.offsets[i][1], t.offsets[i][2]};
  std::sort(v.begin(), v.end());
  const std::array<int, 4> least = v[0];
  for (auto& vertex : v)
    for (int k = 1; k < 4; ++k)
      vertex[k] -= least[k];
  return v;
}

TEST(PeriodicAgainstCGAL, SameTetrahedraOnUniformPoints)
{
  for (std::size_t n : {50, 2000})
  {
    const Points p = fd3test::uniformCube(n, 21);
    std::set<std::array<std::array<int, 4>, 4>> theirs, ours;
    for (const PeriodicTetrahedron& t : cgalPeriodic(p))
      theirs.insert(translated(t));
    const fd3::PeriodicTriangulation core =
      fd3::triangulatePeriodic(p.data(), n, fd3::PeriodicBox());
    ASSERT_EQ(core.status, fd3::Status::Ok);
    for (const PeriodicTetrahedron& t : fd3test::tetrahedraOf(core))
      ours.insert(translated(t));
    EXPECT_EQ(core.numberOfTetrahedra(), ours.size()) << n;
    EXPECT_EQ(ours, theirs) << n;
  }
}

// Weighted: CGAL's Periodic_3_regular_triangulation_3 asks weights below 1/64 of the period
// squared (radii below 1/8): radii up to 0.1 hide a few points.
TEST(PeriodicAgainstCGAL, SameRegularTetrahedraOnUniformPointsWithRadii)
{
  for (std::size_t n : {50, 2000})
  {
    const Points p = fd3test::uniformCube(n, 22);
    std::mt19937_64 random(23);
    std::uniform_real_distribution<double> radius(0.0, 0.1);
    std::vector<double> w(n);
    for (double& x : w)
    {
      const double r = radius(random);
      x = r * r;
    }
    std::size_t hidden = 0;
    std::set<std::array<std::array<int, 4>, 4>> theirs, ours;
    for (const PeriodicTetrahedron& t : cgalPeriodicRegular(p, w, hidden))
      theirs.insert(translated(t));
    const fd3::PeriodicTriangulation core =
      fd3::triangulatePeriodic(p.data(), w.data(), n, fd3::PeriodicBox());
    ASSERT_EQ(core.status, fd3::Status::Ok);
    for (const PeriodicTetrahedron& t : fd3test::tetrahedraOf(core))
      ours.insert(translated(t));
    EXPECT_EQ(core.numberOfTetrahedra(), ours.size()) << n;
    EXPECT_EQ(ours, theirs) << n;
    EXPECT_EQ(core.hidden.size(), hidden) << n;
    if (n == 2000)
      EXPECT_GT(hidden, 0u);
  }
}

} // namespace
