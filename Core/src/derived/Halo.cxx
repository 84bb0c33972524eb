// The points one piece of a distributed point set must send to the others so that each piece can
// build every Delaunay tetrahedron that touches its own points (Funke and Sanders, "Parallel d-D
// Delaunay triangulation in shared and distributed memory", 2017). The reason one exchange is
// enough: if a tetrahedron of the whole set joins a point v of box B to a point q of this piece,
// its empty circumsphere makes v-q a Delaunay edge once v is inserted here, so q is a vertex of a
// tetrahedron (or hull face) of this piece that v conflicts with, and v lies in B: that
// tetrahedron's circumsphere (or the hull face's outer half-space) meets B.
#include "derived/Halo.h"

#include "fd3/Measures.h"

#include <algorithm>
#include <cmath>

namespace fd3
{
namespace
{
/// Beyond this ratio of edge lengths to volume the computed circumcentre is not trusted: the
/// circumsphere is taken to meet every box, which only sends more points than needed.
constexpr double kIllConditioned = 1e8;
/// Relative widening of every sphere and half-space, far above the rounding errors of a
/// circumcentre whose condition is below kIllConditioned.
constexpr double kMargin = 1e-6;

struct Ball
{
  double centre[3];
  double radius2; ///< squared, widened by kMargin
  bool unbounded; ///< too flat to trust: meets every box
};

// Squared lengths throughout: the pass visits every tetrahedron of the mesh, and square roots
// cost as much as the rest of the test.
Ball circumball(const double* a, const double* b, const double* c, const double* d)
{
  const Circumcentre centre = circumcentre(a, b, c, d);
  Ball ball{{0, 0, 0}, 0, true};
  if (!(centre.sixVolume * centre.sixVolume * (kIllConditioned * kIllConditioned) >
        centre.edgeProduct2))
  {
    return ball;
  }
  double r2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    ball.centre[k] = a[k] + centre.offset[k];
    r2 += centre.offset[k] * centre.offset[k];
  }
  ball.radius2 = r2 * ((1 + kMargin) * (1 + kMargin));
  ball.unbounded = false;
  return ball;
}

bool meets(const Ball& ball, const Bounds& box)
{
  if (ball.unbounded)
  {
    return true;
  }
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double gap = std::max({box.lo[k] - ball.centre[k], ball.centre[k] - box.hi[k], 0.0});
    d2 += gap * gap;
  }
  return d2 <= ball.radius2;
}

/// Whether the closed half-space beyond face abc, away from the inner vertex d, meets the box.
bool beyondFaceMeets(
  const double* a, const double* b, const double* c, const double* d, const Bounds& box)
{
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  if ((d[0] - a[0]) * n[0] + (d[1] - a[1]) * n[1] + (d[2] - a[2]) * n[2] > 0)
  {
    n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
  }
  // The box corner farthest along n, and a slack for the rounding of n and of the products.
  double reach = 0, scale = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double corner = n[k] > 0 ? box.hi[k] : box.lo[k];
    reach += n[k] * (corner - a[k]);
    scale += std::abs(n[k]) * (std::abs(corner - a[k]) + std::abs(u[k]) + std::abs(v[k]));
  }
  return reach >= -kMargin * scale;
}
} // namespace

HaloBuilder::HaloBuilder(const std::vector<Bounds>& boxes) : boxes_(boxes), halo_(boxes.size()) {}

void HaloBuilder::tetrahedron(const double* const p[4], const std::uint32_t ids[4])
{
  const Ball ball = circumball(p[0], p[1], p[2], p[3]);
  for (std::size_t b = 0; b < boxes_.size(); ++b)
  {
    if (!boxes_[b].empty() && meets(ball, boxes_[b]))
      halo_[b].insert(halo_[b].end(), ids, ids + 4);
  }
}

void HaloBuilder::hullFace(
  const double* const p[3], const double* inner, const std::uint32_t ids[3])
{
  for (std::size_t b = 0; b < boxes_.size(); ++b)
  {
    if (!boxes_[b].empty() && beyondFaceMeets(p[0], p[1], p[2], inner, boxes_[b]))
      halo_[b].insert(halo_[b].end(), ids, ids + 3);
  }
}

std::vector<std::vector<std::uint32_t>> HaloBuilder::take()
{
  for (auto& ids : halo_)
  {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  }
  return std::move(halo_);
}

std::vector<std::vector<std::uint32_t>> haloVertices(
  const double* xyz, const Triangulation& triangulation, const std::vector<Bounds>& boxes)
{
  HaloBuilder halo(boxes);
  auto point = [xyz](std::uint32_t id) { return xyz + 3 * std::size_t(id); };
  for (std::size_t t = 0; t < triangulation.numberOfTetrahedra(); ++t)
  {
    const std::uint32_t* v = triangulation.tetrahedra.data() + 4 * t;
    const double* p[4] = {point(v[0]), point(v[1]), point(v[2]), point(v[3])};
    halo.tetrahedron(p, v);
    for (int f = 0; f < 4; ++f)
    {
      if (triangulation.neighbors[4 * t + f] == kNoNeighbor)
      {
        const std::uint32_t face[3] = {v[(f + 1) % 4], v[(f + 2) % 4], v[(f + 3) % 4]};
        const double* q[3] = {point(face[0]), point(face[1]), point(face[2])};
        halo.hullFace(q, p[f], face);
      }
    }
  }
  return halo.take();
}

} // namespace fd3
