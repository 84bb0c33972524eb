// The Delaunay tessellation field estimate (Schaap and van de Weygaert, 2000): each vertex's
// density is 4 times its mass over the volume of its star, so that the piecewise-linear field
// through the vertices integrates over the hull to the total mass, one per finite input point.
//
// Volumes are summed as a double times a power of two: a tetrahedron of edges near 1e-150 has a
// volume near 1e-450, which no double holds, and whose density (near 1e450) rounds to infinity
// rather than to whatever an underflowed volume would give. Each volume comes from its vertices in
// one order, whatever the mesh's, so that every run (and every MPI rank) computes it alike.
#include "derived/Density.h"
#include "exact/Predicates.h"
#include "fd3/Delaunay.h"
#include "fd3/Periodic.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fd3
{
namespace
{
/// mantissa * 2^exponent.
struct ScaledSum
{
  double mantissa = 0;
  int exponent = 0;

  void add(double m, int e)
  {
    if (mantissa == 0 || e > exponent + 60)
    {
      mantissa = (mantissa == 0 ? 0 : std::ldexp(mantissa, exponent - e)) + m;
      exponent = e;
    }
    else
      mantissa += std::ldexp(m, e - exponent);
  }
};

/// Six times a tetrahedron's volume as mantissa * 2^exponent, the same whatever the order of its
/// vertices: from the edges of a path through them in lexicographic order (each edge scaled by a
/// power of two, exactly, to a length near 1), a path that keeps the digits of close points'
/// edges beside far ones; exactly where that still cancels too many digits.
void sixVolumeScaled(const double* const vertices[4], double& mantissa, int& exponent)
{
  const double* p[4] = {vertices[0], vertices[1], vertices[2], vertices[3]};
  std::sort(p, p + 4, [](const double* a, const double* b) {
    return std::lexicographical_compare(a, a + 3, b, b + 3);
  });
  double e[3][3], size = 1;
  exponent = 0;
  for (int i = 0; i < 3; ++i)
  {
    double longest = 0;
    for (int k = 0; k < 3; ++k)
    {
      e[i][k] = p[i + 1][k] - p[i][k];
      longest = std::max(longest, std::fabs(e[i][k]));
    }
    if (!(longest > 0) || !std::isfinite(longest))
    {
      mantissa = 0;
      return;
    }
    const int scale = std::ilogb(longest);
    for (double& x : e[i])
      x = std::ldexp(x, -scale);
    exponent += scale;
    size *= std::sqrt(e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2]);
  }
  mantissa = std::fabs(e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
    e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
    e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]));
  // The determinant's rounding is a few ulps of the edges' product: below 1e-8 of it, fewer than
  // 8 digits would be right.
  if (mantissa < 1e-8 * size)
    exactSixVolume(p[0], p[1], p[2], p[3], mantissa, exponent);
}

/// The estimate from tetrahedra `tets` on vertices at corner(v), each vertex counted at its input
/// point source(v), or at none where that is `count` or more (a piece's other points).
template <typename Corner, typename Source>
std::vector<double> densitiesOf(std::size_t count, const IdArray& tets,
  const std::uint32_t* representative, Corner corner, Source source)
{
  std::vector<ScaledSum> star(count);
  std::vector<double> mass(count, 0);
  for (std::size_t t = 0; t < tets.size() / 4; ++t)
  {
    const std::uint32_t* v = &tets[4 * t];
    const double* p[4] = {corner(v[0]), corner(v[1]), corner(v[2]), corner(v[3])};
    double mantissa;
    int exponent;
    sixVolumeScaled(p, mantissa, exponent);
    for (int k = 0; k < 4; ++k)
    {
      const std::uint32_t s = source(v[k]);
      if (s < count)
        star[s].add(mantissa, exponent);
    }
  }
  // A point merged into a vertex (an exact duplicate, or one within the tolerance) adds to its
  // mass, and has its density.
  for (std::size_t i = 0; i < count; ++i)
    if (representative[i] < count)
      mass[representative[i]] += 1;
  std::vector<double> density(count, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::uint32_t v = representative[i];
    if (v < count && star[v].mantissa > 0) // 4 m / (six volume / 6)
      density[i] = std::ldexp(24 * mass[v] / star[v].mantissa, -star[v].exponent);
  }
  return density;
}
} // namespace

std::vector<double> densities(
  const double* xyz, std::size_t count, const Triangulation& triangulation)
{
  if (triangulation.status != Status::Ok)
    return std::vector<double>(count, std::numeric_limits<double>::quiet_NaN());
  return densitiesOf(
    count, triangulation.tetrahedra, triangulation.representative.data(),
    [xyz](std::uint32_t v) { return xyz + 3 * std::size_t(v); }, [](std::uint32_t v) { return v; });
}

std::vector<double> densities(const double* xyz, std::size_t count,
  const PeriodicTriangulation& triangulation, const PeriodicPlacement& placement)
{
  if (triangulation.status != Status::Ok)
    return std::vector<double>(count, std::numeric_limits<double>::quiet_NaN());
  const double* images = placement.imagePoints.data();
  const std::uint32_t* sources = placement.imageSources.data();
  return densitiesOf(
    count, placement.tetrahedra, triangulation.representative.data(),
    [=](
      std::uint32_t v) { return v < count ? xyz + 3 * std::size_t(v) : images + 3 * (v - count); },
    [=](std::uint32_t v) { return v < count ? v : sources[v - count]; });
}

std::vector<double> densitiesOfCorners(std::size_t count, const IdArray& tets,
  const double* corners, const std::uint32_t* source, const std::uint32_t* representative)
{
  return densitiesOf(
    count, tets, representative, [=](std::uint32_t v) { return corners + 3 * std::size_t(v); },
    [=](std::uint32_t v) { return source[v]; });
}

} // namespace fd3
