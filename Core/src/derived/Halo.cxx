// The points one piece of a distributed point set must send to the others so that each piece can
// build every Delaunay tetrahedron that touches its own points (Funke and Sanders, "Parallel d-D
// Delaunay triangulation in shared and distributed memory", 2017). The reason one exchange is
// enough: if a tetrahedron of the whole set joins a point v of box B to a point q of this piece,
// its empty circumsphere makes v-q a Delaunay edge once v is inserted here, so q is a vertex of a
// tetrahedron (or hull face) of this piece that v conflicts with, and v lies in B: that
// tetrahedron's circumsphere (or the hull face's outer half-space) meets B.
//
// Weighted points (the regular tetrahedralization) keep the argument, with power distances. The
// power of a point x of weight w_x to the sphere orthogonal to q centred at c, |x - c|^2 - w_x -
// (|q - c|^2 - w_q), is affine in c, and q's power cell in this piece is spanned by the
// orthocentres of its tetrahedra (and the outer normals of its hull faces). So where a
// tetrahedron of the whole set joins q to a point v of box B, some tetrahedron of this piece
// around q has v in conflict with its orthogonal sphere: v lies within the ball of the sphere's
// centre and squared radius r^2 + w_v. A point v of B that the whole set hides lies in a
// tetrahedron of the whole set, within the ball of squared radius r^2 + (its vertices' largest
// weight), and the same affine argument finds a tetrahedron of this piece whose ball of squared
// radius r^2 + that weight holds v. Both balls are within the one of squared radius r^2 + W, W the
// largest weight of all the pieces' points: the tetrahedra whose such ball meets B send their
// vertices, and B then has every tetrahedron of the whole set around its points, and every one
// that hides a point of it.
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

/// The ball of the orthogonal sphere of tetrahedron p (weights w) with `heaviest` added to its
/// squared radius. Its centre's rounding is bounded by kMargin times the largest term of its
/// formula, which also widens the radius; where that bound is not finite, the ball is unbounded.
Ball orthoball(const double* const p[4], const double w[4], double heaviest)
{
  double edge[3][3], lowered[3], length[3];
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
      edge[i][k] = p[i + 1][k] - p[0][k];
    lowered[i] = w[i + 1] - w[0];
    length[i] =
      std::sqrt(edge[i][0] * edge[i][0] + edge[i][1] * edge[i][1] + edge[i][2] * edge[i][2]);
  }
  const Circumcentre centre = circumcentreOfEdges(edge[0], edge[1], edge[2], lowered);
  Ball ball{{0, 0, 0}, 0, true};
  if (!(std::abs(centre.sixVolume) * kIllConditioned > length[0] * length[1] * length[2]))
    return ball;
  double term = 0; // a lifted length's bound times the other two edges' lengths, the largest
  for (int i = 0; i < 3; ++i)
  {
    const double lifted = length[i] * length[i] + std::abs(lowered[i]);
    term = std::max(term, lifted * length[(i + 1) % 3] * length[(i + 2) % 3]);
  }
  const double slack = kMargin * 3 * term / (2 * std::abs(centre.sixVolume));
  if (!std::isfinite(slack))
    return ball;
  double r2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    ball.centre[k] = p[0][k] + centre.offset[k];
    r2 += centre.offset[k] * centre.offset[k];
  }
  const double offset = std::sqrt(r2);
  const double reach2 = r2 - w[0] + heaviest +
    kMargin * (r2 + std::abs(w[0]) + std::abs(heaviest)) + slack * (2 * offset + slack);
  if (!std::isfinite(reach2))
    return ball;
  ball.unbounded = false;
  if (reach2 < 0) // no point of the pieces can conflict with the sphere
  {
    ball.radius2 = -1;
    return ball;
  }
  const double radius = std::sqrt(reach2) * (1 + kMargin) + slack;
  ball.radius2 = radius * radius;
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

HaloBuilder::HaloBuilder(const std::vector<Bounds>& boxes, double heaviest)
  : boxes_(boxes), heaviest_(heaviest), halo_(boxes.size())
{}

void HaloBuilder::tetrahedron(
  const double* const p[4], const std::uint32_t ids[4], const double* weights)
{
  const Ball ball = weights ? orthoball(p, weights, heaviest_) : circumball(p[0], p[1], p[2], p[3]);
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
  return haloVertices(xyz, nullptr, triangulation, boxes, -HUGE_VAL);
}

std::vector<std::vector<std::uint32_t>> haloVertices(const double* xyz, const double* weights,
  const Triangulation& triangulation, const std::vector<Bounds>& boxes, double heaviest)
{
  HaloBuilder halo(boxes, heaviest);
  auto point = [xyz](std::uint32_t id) { return xyz + 3 * std::size_t(id); };
  for (std::size_t t = 0; t < triangulation.numberOfTetrahedra(); ++t)
  {
    const std::uint32_t* v = triangulation.tetrahedra.data() + 4 * t;
    const double* p[4] = {point(v[0]), point(v[1]), point(v[2]), point(v[3])};
    if (weights)
    {
      const double w[4] = {weights[v[0]], weights[v[1]], weights[v[2]], weights[v[3]]};
      halo.tetrahedron(p, v, w);
    }
    else
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
