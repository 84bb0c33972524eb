// Helpers shared by the Core tests.
#ifndef fd3_CoreTestUtilities_h
#define fd3_CoreTestUtilities_h

#include "ExactValidator.h"
#include "PointSets.h"
#include "fd3/Delaunay.h"
#include "fd3/Distributed.h"

#include <gtest/gtest.h>

#include <array>
#include <string>

namespace fd3test
{
/// Points per set in the tests that run on many threads (fewer under the thread sanitizer, which
/// is slow).
#ifdef FD3_THREAD_SANITIZER
constexpr std::size_t kThreadTestPoints = 6000;
#else
constexpr std::size_t kThreadTestPoints = 40000;
#endif

/// The tetrahedralization of `p`, checked by the exact validator (a valid Delaunay
/// tetrahedralization of the distinct points, each of them a vertex) and by its own figures: every
/// point a vertex or counted as left out, a neighbour entry per vertex entry where asked for.
/// `what` names the case in a failure's message.
inline fd3::Triangulation triangulateAndCheck(
  const Points& p, const fd3::Options& options = {}, const std::string& what = "")
{
  const std::size_t n = p.size() / 3;
  fd3::Triangulation result = fd3::triangulate(p.data(), n, options);
  EXPECT_EQ(result.status, fd3::Status::Ok) << what << ": " << fd3::toString(result.status);
  const ValidityReport report = checkTriangulation(p.data(), n, result.tetrahedra);
  EXPECT_TRUE(report.valid()) << what << ": " << report.summary();
  const fd3::Statistics& s = result.stats;
  EXPECT_EQ(s.insertedPoints, report.distinctPoints) << what;
  EXPECT_EQ(s.insertedPoints + s.duplicatesMerged + s.closePointsSkipped + s.nonFinitePoints, n)
    << what;
  if (options.computeNeighbors)
    EXPECT_EQ(result.neighbors.size(), result.tetrahedra.size()) << what;
  return result;
}

/// The exact frame of a whole point set, as a distributed run computes it from every piece.
inline fd3::Frame frameOf(const Points& p)
{
  return fd3::frameOf(p.data(), p.size() / 3);
}

/// The box {xmin, xmax, ymin, ymax, zmin, zmax}.
inline fd3::Bounds boxOf(const std::array<double, 6>& minMax)
{
  return fd3::Bounds::fromMinMax(minMax.data());
}
} // namespace fd3test

#endif
