// The Delaunay tessellation field estimate (Schaap and van de Weygaert, 2000): each vertex's
// density is 4 times its mass over the volume of its star, so that the piecewise-linear field
// through the vertices integrates over the hull to the total mass, one per finite input point.
#include "fd3/Delaunay.h"
#include "fd3/Measures.h"

#include <cmath>
#include <limits>

namespace fd3
{

std::vector<double> densities(
  const double* xyz, std::size_t count, const Triangulation& triangulation)
{
  std::vector<double> density(count, std::numeric_limits<double>::quiet_NaN());
  if (triangulation.status != Status::Ok)
    return density;
  std::vector<double> starVolume(count, 0), mass(count, 0);
  const std::uint32_t* t4 = triangulation.tetrahedra.data();
  for (std::size_t t = 0; t < triangulation.numberOfTetrahedra(); ++t)
  {
    const std::uint32_t* v = t4 + 4 * t;
    const double volume =
      std::fabs(sixVolume(&xyz[3 * std::size_t(v[0])], &xyz[3 * std::size_t(v[1])],
        &xyz[3 * std::size_t(v[2])], &xyz[3 * std::size_t(v[3])])) /
      6;
    for (int k = 0; k < 4; ++k)
      starVolume[v[k]] += volume;
  }
  // A point merged into a vertex (an exact duplicate, or one within the tolerance) adds to its
  // mass, and has its density.
  for (std::size_t i = 0; i < count; ++i)
    if (triangulation.representative[i] != kNoPoint)
      mass[triangulation.representative[i]] += 1;
  for (std::size_t i = 0; i < count; ++i)
  {
    const std::uint32_t v = triangulation.representative[i];
    if (v != kNoPoint && starVolume[v] > 0)
      density[i] = 4 * mass[v] / starVolume[v];
  }
  return density;
}

} // namespace fd3
