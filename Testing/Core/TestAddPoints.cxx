// fd3::IncrementalDelaunay, the mesh that points can be added to (the distributed filter adds the
// ghost points of other ranks to it): whatever the batches, the tetrahedra are those of all the
// points at once, exactly valid; a mesh that cannot start yet keeps its points.
#include "CoreTestUtilities.h"
#include "ExactValidator.h"
#include "PointSets.h"
#include "exact/Frame.h"
#include "fd3/Distributed.h"
#include "fd3/Voronoi.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace
{
/// Builds the mesh of `p` from its first `first` points, with `room` for added ones, then adds the
/// rest in batches of the given sizes (the last batch takes what is left).
fd3::Triangulation inBatches(const fd3test::Points& p, std::size_t first,
  const std::vector<std::size_t>& batches, const fd3::Options& options, std::size_t room = 0)
{
  fd3::IncrementalDelaunay mesh(p.data(), first, options, fd3test::frameOf(p), room);
  std::size_t done = first;
  for (std::size_t b = 0; b <= batches.size() && done < p.size() / 3; ++b)
  {
    const std::size_t count =
      b < batches.size() ? std::min(batches[b], p.size() / 3 - done) : p.size() / 3 - done;
    mesh.add(p.data() + 3 * done, count);
    done += count;
  }
  return mesh.snapshot();
}

TEST(AddPoints, SameTetrahedraAsAllAtOnceOnEveryPointSet)
{
  for (const std::string& kind : fd3test::pointSetNames())
  {
    SCOPED_TRACE(kind);
    const fd3test::Points p = fd3test::generate(kind, 12000, 21);
    fd3::Options options;
    options.pointsPerThread = 256;
    const fd3::Triangulation whole = fd3::triangulate(p.data(), p.size() / 3, options);
    ASSERT_EQ(whole.status, fd3::Status::Ok);
    const auto reference = fd3test::canonicalTetrahedra(whole.tetrahedra);
    // Room for none of the added points, for some (the vertex records grow in the third batch),
    // and for all.
    for (const auto& [threads, room] :
      {std::pair<int, std::size_t>{1, 0}, {3, 0}, {1, 1600}, {3, 20000}})
    {
      SCOPED_TRACE(std::to_string(threads) + " threads, room " + std::to_string(room));
      options.threads = threads;
      const fd3::Triangulation added = inBatches(p, p.size() / 6, {7, 1500, 3000}, options, room);
      ASSERT_EQ(added.status, fd3::Status::Ok);
      EXPECT_EQ(fd3test::canonicalTetrahedra(added.tetrahedra), reference);
      EXPECT_EQ(added.stats.inputPoints, p.size() / 3);
      EXPECT_EQ(added.stats.insertedPoints + added.stats.duplicatesMerged, p.size() / 3);
      const auto report = fd3test::checkTriangulation(p.data(), p.size() / 3, added.tetrahedra);
      EXPECT_TRUE(report.valid()) << report.summary();
    }
  }
}

// A lattice makes the predicates compute exactly in floats; points off the lattice added later,
// some nearly cospherical with lattice points, must take that away again.
TEST(AddPoints, PointsOffTheLatticeRetuneThePredicates)
{
  fd3test::Points p = fd3test::lattice(9);
  const std::size_t latticePoints = p.size() / 3;
  for (std::size_t i = 0; i < 300; ++i)
  {
    const double* q = &p[3 * (i * 7 % latticePoints)];
    const double offset = i % 2 ? 1e-9 : 0.37;
    p.insert(p.end(), {q[0] + offset * 0.5, q[1] + offset * 0.25, q[2] + offset * 0.125});
  }
  fd3::Options options;
  fd3::IncrementalDelaunay mesh(p.data(), latticePoints, options, fd3test::frameOf(p));
  mesh.add(p.data() + 3 * latticePoints, p.size() / 3 - latticePoints);
  const fd3::Triangulation added = mesh.snapshot();
  ASSERT_EQ(added.status, fd3::Status::Ok);
  const auto report = fd3test::checkTriangulation(p.data(), p.size() / 3, added.tetrahedra);
  EXPECT_TRUE(report.valid()) << report.summary();
  const fd3::Triangulation whole = fd3::triangulate(p.data(), p.size() / 3, options);
  EXPECT_EQ(
    fd3test::canonicalTetrahedra(added.tetrahedra), fd3test::canonicalTetrahedra(whole.tetrahedra));
}

// The predicates' static bounds come from the first points' box; points added far beyond it (a
// Voronoi run's far points, the corners of a cube about them, cospherical) must widen them, else
// the float filters pass signs that rounding decides. Weighted too, where the power test has no
// relative filter to fall back on.
TEST(AddPoints, PointsFarBeyondTheFirstOnesWidenTheStaticBounds)
{
  for (const char* kind : {"cube", "clusters", "sphere", "lattice"})
    for (const bool weighted : {false, true})
    {
      SCOPED_TRACE(std::string(kind) + (weighted ? ", weighted" : ""));
      fd3test::Points p = fd3test::generate(kind, 3000, 31);
      const std::size_t first = p.size() / 3;
      const fd3::Bounds box = fd3::finiteBounds(p.data(), first);
      const std::vector<double> far = fd3::voronoiFarPoints(box, box);
      p.insert(p.end(), far.begin(), far.end());
      const std::size_t n = p.size() / 3;
      std::vector<double> weights(n, 0.0);
      for (std::size_t i = 0; i < first; ++i)
        weights[i] = 1e-3 * box.diagonal() * box.diagonal() * double(i % 7);
      const double* w = weighted ? weights.data() : nullptr;
      fd3::IncrementalDelaunay mesh(p.data(), first, fd3::Options(), fd3test::frameOf(p), 8, w);
      mesh.add(p.data() + 3 * first, n - first, weighted ? w + first : nullptr);
      const fd3::Triangulation added = mesh.release();
      ASSERT_EQ(added.status, fd3::Status::Ok);
      fd3test::ValidityOptions check;
      check.weights = w;
      check.hidden = added.hidden;
      const auto report = fd3test::checkTriangulation(p.data(), n, added.tetrahedra, check);
      EXPECT_TRUE(report.valid()) << report.summary();
    }
}

TEST(AddPoints, TooFewOrCoplanarPointsWaitForMore)
{
  const fd3test::Points p = fd3test::uniformCube(2000, 5);
  fd3test::Points flat = {0.1, 0.1, 0.5, 0.9, 0.2, 0.5, 0.4, 0.8, 0.5, 0.5, 0.5, 0.5};
  fd3test::Points all = flat;
  all.insert(all.end(), p.begin(), p.end());
  fd3::Options options;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const fd3test::Points firstTwo = {flat[0], flat[1], flat[2], nan, 0, 0};
  fd3::IncrementalDelaunay mesh(firstTwo.data(), 2, options, fd3test::frameOf(all));
  EXPECT_EQ(mesh.status(), fd3::Status::TooFewPoints);
  EXPECT_EQ(mesh.snapshot().status, fd3::Status::TooFewPoints);
  mesh.add(flat.data() + 3, 3);
  EXPECT_EQ(mesh.status(), fd3::Status::Degenerate);
  mesh.add(p.data(), p.size() / 3);
  ASSERT_EQ(mesh.status(), fd3::Status::Ok);
  const fd3::Triangulation out = mesh.snapshot();
  ASSERT_EQ(out.status, fd3::Status::Ok);
  EXPECT_EQ(out.stats.inputPoints, 2 + 3 + p.size() / 3);
  EXPECT_EQ(out.stats.nonFinitePoints, 1u);
  ASSERT_EQ(out.representative.size(), out.stats.inputPoints);
  EXPECT_EQ(out.representative[1], fd3::kNoPoint);
  // Point ids follow the batches: the NaN is id 1.
  fd3test::Points byId = firstTwo;
  byId.insert(byId.end(), all.begin() + 3, all.end());
  const auto report = fd3test::checkTriangulation(byId.data(), byId.size() / 3, out.tetrahedra);
  EXPECT_TRUE(report.valid()) << report.summary();
}

TEST(AddPoints, SnapshotsLeaveTheMeshToGrowAndReleaseEndsIt)
{
  const fd3test::Points p = fd3test::uniformBall(3000, 9);
  fd3::Options options;
  options.computeNeighbors = true;
  fd3::IncrementalDelaunay mesh(p.data(), 1000, options, fd3test::frameOf(p));
  const fd3::Triangulation early = mesh.snapshot();
  ASSERT_EQ(early.status, fd3::Status::Ok);
  EXPECT_EQ(early.neighbors.size(), early.tetrahedra.size());
  EXPECT_TRUE(fd3test::checkTriangulation(p.data(), 1000, early.tetrahedra).valid());
  mesh.add(p.data() + 3 * 1000, 2000);
  const fd3::Triangulation whole = mesh.release();
  ASSERT_EQ(whole.status, fd3::Status::Ok);
  EXPECT_TRUE(fd3test::checkTriangulation(p.data(), 3000, whole.tetrahedra).valid());
  EXPECT_THROW(mesh.add(p.data(), 1), std::logic_error);
}

bool sameBits(const double* a, const double* b, std::size_t count)
{
  return std::memcmp(a, b, count * sizeof(double)) == 0;
}

// A mesh that takes its points (the distributed filter's) frees them once its vertex records hold
// them, and gives them back bit for bit: far from the origin (the frame's shift), with exact
// duplicates within a batch and across batches, and points that are not finite.
TEST(AddPoints, TakenPointsComeBackBitForBit)
{
  fd3test::Points p = fd3test::uniformCube(4000, 17);
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = 5e5 + std::round(p[i] * 1e4) / 100; // a 1 cm grid near 5e5, as LiDAR coordinates
  for (std::size_t k = 0; k < 40; ++k) // duplicates: of the first batch, in it and in the second
    std::copy_n(p.begin() + 3 * (37 * k), 3, p.begin() + 3 * (1000 + 51 * k));
  const fd3::Frame frame = fd3test::frameOf(p);
  p[3 * 1500 + 1] = std::numeric_limits<double>::quiet_NaN();
  p[3 * 2500 + 2] = -std::numeric_limits<double>::infinity();
  ASSERT_NE(frame.shift[0], 0.0);
  ASSERT_TRUE(fd3::recoverable(frame, p.data(), p.size() / 3));

  fd3::IncrementalDelaunay mesh(
    fd3::Coordinates(p.begin(), p.begin() + 3 * 2000), fd3::Options(), frame);
  EXPECT_EQ(mesh.heldPoints(), 0u);
  const std::vector<std::vector<std::uint32_t>> vertices = {{0, 1, 999}, {}, {1999, 0}};
  const std::vector<std::vector<double>> some = mesh.points(vertices);
  ASSERT_EQ(some.size(), vertices.size());
  for (std::size_t l = 0; l < vertices.size(); ++l)
  {
    ASSERT_EQ(some[l].size(), 3 * vertices[l].size());
    for (std::size_t k = 0; k < vertices[l].size(); ++k)
      EXPECT_TRUE(sameBits(&some[l][3 * k], &p[3 * vertices[l][k]], 3));
  }
  EXPECT_THROW(mesh.points({{1000}}), std::invalid_argument); // a duplicate of point 0
  mesh.add(p.data() + 3 * 2000, p.size() / 3 - 2000);
  EXPECT_EQ(mesh.heldPoints(), p.size() / 3 - 2000); // another's points: held as they are

  fd3::Coordinates back;
  const fd3::Triangulation out = mesh.release(back);
  ASSERT_EQ(out.status, fd3::Status::Ok);
  EXPECT_EQ(out.stats.duplicatesMerged, 40u);
  ASSERT_EQ(back.size(), p.size());
  for (std::size_t i = 0; i < p.size() / 3; ++i)
    EXPECT_TRUE(sameBits(&back[3 * i], &p[3 * i], 3)) << i;
  EXPECT_THROW(mesh.release(back), std::logic_error);
  EXPECT_THROW(mesh.snapshot(), std::logic_error);
}

// Where the records would not give them back, or there are no records yet, the mesh holds the
// points.
TEST(AddPoints, TakenPointsAreHeldWhereRecordsCannotGiveThemBack)
{
  // A -0: its duplicate at +0 would come back as +0.
  fd3test::Points q = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  EXPECT_TRUE(fd3::recoverable(fd3test::frameOf(q), q.data(), 5));
  q[0] = -0.0;
  EXPECT_FALSE(fd3::recoverable(fd3test::frameOf(q), q.data(), 5));
  fd3::IncrementalDelaunay signedZero(
    fd3::Coordinates(q.begin(), q.end()), fd3::Options(), fd3test::frameOf(q));
  EXPECT_EQ(signedZero.heldPoints(), 5u);
  fd3::Coordinates back;
  EXPECT_EQ(signedZero.release(back).stats.duplicatesMerged, 1u);
  ASSERT_EQ(back.size(), q.size());
  EXPECT_TRUE(sameBits(back.data(), q.data(), q.size()));

  // A coordinate that the scaled frame takes below the smallest double: that frame does not hold
  // the points, and the identity frame they get instead gives them back.
  q = {-1e300, 0, 0, 1e300, 0, 0, 0, 1, 0, 1e-300, 0, 1};
  const double minMax[6] = {-1e300, 1e300, 0, 1, 0, 1};
  const bool exact[3] = {true, true, true};
  const fd3::Frame scaled = fd3::frameFor(fd3::Bounds::fromMinMax(minMax), exact);
  EXPECT_FALSE(fd3::fitsFrame(scaled, q.data(), 4));
  EXPECT_FALSE(fd3::recoverable(scaled, q.data(), 4));
  EXPECT_TRUE(fd3test::frameOf(q).identity);
  EXPECT_TRUE(fd3::recoverable(fd3test::frameOf(q), q.data(), 4));

  // With a tolerance, a skipped point has no record.
  const fd3test::Points p = fd3test::uniformCube(300, 5);
  fd3::Options options;
  options.tolerance = 1e-12;
  fd3::IncrementalDelaunay tolerant(
    fd3::Coordinates(p.begin(), p.end()), options, fd3test::frameOf(p));
  EXPECT_EQ(tolerant.heldPoints(), 300u);

  // No records before the mesh starts: three points, then the rest.
  fd3::IncrementalDelaunay few(
    fd3::Coordinates(p.begin(), p.begin() + 9), fd3::Options(), fd3test::frameOf(p));
  EXPECT_EQ(few.status(), fd3::Status::TooFewPoints);
  EXPECT_EQ(few.heldPoints(), 3u);
  EXPECT_EQ(few.points({{2, 0}})[0], std::vector<double>({p[6], p[7], p[8], p[0], p[1], p[2]}));
  few.add(p.data() + 9, p.size() / 3 - 3);
  EXPECT_EQ(few.status(), fd3::Status::Ok);
  EXPECT_EQ(few.heldPoints(), 0u);
  few.release(back);
  EXPECT_TRUE(sameBits(back.data(), p.data(), p.size()));

  // A mesh that reads its points leaves them to the caller.
  fd3::IncrementalDelaunay reads(p.data(), 3, fd3::Options(), fd3test::frameOf(p));
  EXPECT_EQ(reads.heldPoints(), 3u);
  reads.add(p.data() + 9, p.size() / 3 - 3);
  EXPECT_EQ(reads.heldPoints(), 0u);
  EXPECT_THROW(reads.release(back), std::logic_error);
}

TEST(AddPoints, PointsOutsideTheFrameAreRefused)
{
  const fd3test::Points p = fd3test::uniformCube(500, 3);
  fd3::IncrementalDelaunay mesh(p.data(), p.size() / 3, fd3::Options(), fd3test::frameOf(p));
  const double outside[3] = {2.0, 0.5, 0.5};
  EXPECT_THROW(mesh.add(outside, 1), std::invalid_argument);
  EXPECT_EQ(mesh.status(), fd3::Status::Ok);
}
} // namespace

namespace
{
/// A mesh kept current from addOne()'s changes alone, as vtkFastDelaunay3D's incremental API
/// keeps its vtkUnstructuredGrid: each live tetrahedron's sorted point ids, by id.
class MirroredMesh
{
public:
  explicit MirroredMesh(const fd3::IncrementalDelaunay& mesh) : mesh_(mesh)
  {
    for (const std::uint32_t t : mesh.liveTetrahedra())
      make(t);
  }
  void apply(const fd3::MeshChange& change)
  {
    for (const std::uint32_t t : change.deleted)
      ASSERT_EQ(live_.erase(t), 1u) << "tetrahedron " << t << " deleted twice or never made";
    for (const std::uint32_t t : change.made)
      make(t);
  }
  std::vector<std::array<std::uint32_t, 4>> tetrahedra() const
  {
    std::vector<std::array<std::uint32_t, 4>> all;
    for (const auto& entry : live_)
      all.push_back(entry.second);
    std::sort(all.begin(), all.end());
    return all;
  }

private:
  void make(std::uint32_t t)
  {
    std::array<std::uint32_t, 4> ids;
    mesh_.tetrahedron(t, ids.data());
    std::sort(ids.begin(), ids.end());
    EXPECT_TRUE(live_.emplace(t, ids).second) << "tetrahedron " << t << " made while live";
  }
  const fd3::IncrementalDelaunay& mesh_;
  std::map<std::uint32_t, std::array<std::uint32_t, 4>> live_;
};
} // namespace

// Points added one at a time with the changes reported: a mesh kept current from those changes
// alone holds the tetrahedra of all the points at once, after every insertion on a lattice (ties)
// and at the end on uniform points; repeats and non-finite points change nothing.
TEST(AddPoints, OneAtATimeReportsEveryChange)
{
  for (const std::string kind : {"cube", "lattice"})
  {
    SCOPED_TRACE(kind);
    const fd3test::Points p = fd3test::generate(kind, kind == std::string("cube") ? 3000 : 300, 4);
    const std::size_t n = p.size() / 3, first = n / 4; // a lattice's first plane is flat
    fd3::IncrementalDelaunay mesh(p.data(), first, fd3::Options(), fd3test::frameOf(p));
    ASSERT_EQ(mesh.status(), fd3::Status::Ok);
    MirroredMesh mirror(mesh);
    fd3::MeshChange change;
    for (std::size_t i = first; i < n; ++i)
    {
      ASSERT_TRUE(mesh.addOne(&p[3 * i], change)) << "point " << i;
      EXPECT_FALSE(change.made.empty());
      mirror.apply(change);
      if (kind == std::string("lattice") || i + 1 == n)
        ASSERT_EQ(mirror.tetrahedra(), fd3test::canonicalTetrahedra(mesh.snapshot().tetrahedra))
          << "after point " << i;
    }
    const fd3::Triangulation whole = fd3::triangulate(p.data(), n, fd3::Options());
    EXPECT_EQ(mirror.tetrahedra(), fd3test::canonicalTetrahedra(whole.tetrahedra));
    // A repeat of a vertex and a NaN point take ids but change nothing.
    EXPECT_FALSE(mesh.addOne(&p[3 * 7], change));
    EXPECT_TRUE(change.deleted.empty() && change.made.empty());
    const double nan[3] = {std::nan(""), 0, 0};
    EXPECT_FALSE(mesh.addOne(nan, change));
    const fd3::Triangulation after = mesh.snapshot();
    EXPECT_EQ(after.representative[n], 7u);
    EXPECT_EQ(after.representative[n + 1], fd3::kNoPoint);
    EXPECT_EQ(after.stats.duplicatesMerged, 1u);
    EXPECT_EQ(after.stats.nonFinitePoints, 1u);
    const double outside[3] = {1e9, 0, 0};
    EXPECT_THROW(mesh.addOne(outside, change), std::invalid_argument);
  }
  // A mesh with no tetrahedron yet has nothing to report changes of.
  const double three[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  fd3::IncrementalDelaunay few(three, 3, fd3::Options(), fd3::frameOf(three, 3));
  fd3::MeshChange change;
  EXPECT_THROW(few.addOne(three, change), std::logic_error);
}
