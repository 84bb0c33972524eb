// The Voronoi vertices (step 2 of VoronoiCells.cxx): each tetrahedron's circumcentre (for weighted
// points its orthocentre, the same formula with the weights in the squared lengths), computed
// once from its vertices in sorted order on edges scaled near 1 (in double-double where the
// tetrahedron is flat, exactly where even that loses the digits), and the output point of each
// centre in the box.
#include "voronoi/Circumcentres.h"

#include "exact/DoubleDouble.h"
#include "exact/Predicates.h"
#include "fd3/Measures.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace fd3::voronoi
{
namespace
{
/// The circumcentre's offset from the first vertex, in double-double from the exact edges (each
/// scaled by `down`, a power of two): for flat tetrahedra, whose offset in doubles loses the
/// digits that cancel in its determinants.
void circumcentreInDoubleDouble(const double* xyz, const double* weights, const std::uint32_t* ids,
  double down, double up, double* offset)
{
  DoubleDouble e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
    {
      e[i][k] = DoubleDouble::difference(
        xyz[3 * std::size_t(ids[i + 1]) + k], xyz[3 * std::size_t(ids[0]) + k]);
      e[i][k].hi *= down;
      e[i][k].lo *= down;
    }
  auto crossDD = [](const DoubleDouble* a, const DoubleDouble* b, DoubleDouble* out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
  };
  auto dotDD = [](const DoubleDouble* a, const DoubleDouble* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  DoubleDouble vw[3], wu[3], uv[3];
  crossDD(e[1], e[2], vw);
  crossDD(e[2], e[0], wu);
  crossDD(e[0], e[1], uv);
  DoubleDouble lift[3] = {dotDD(e[0], e[0]), dotDD(e[1], e[1]), dotDD(e[2], e[2])};
  const double twiceVolume = 2 * dotDD(e[0], vw).value();
  const double edgeProduct = std::sqrt(lift[0].value() * lift[1].value() * lift[2].value());
  if (weights)
    for (int i = 0; i < 3; ++i)
    {
      DoubleDouble dw = DoubleDouble::difference(weights[ids[i + 1]], weights[ids[0]]);
      dw.hi *= down * down;
      dw.lo *= down * down;
      lift[i] = lift[i] - dw;
    }
  // The volume's rounding in double-double is a few 2^-106 of the edges' product; below
  // kTrustedFlatness of that product the offset would keep fewer than about 12 digits (three
  // points of a speck far smaller than its distance to the fourth): computed exactly instead.
  constexpr double kTrustedFlatness = 1e-18;
  if (!(std::fabs(twiceVolume) > 2 * kTrustedFlatness * edgeProduct))
  {
    const double* p[4] = {&xyz[3 * std::size_t(ids[0])], &xyz[3 * std::size_t(ids[1])],
      &xyz[3 * std::size_t(ids[2])], &xyz[3 * std::size_t(ids[3])]};
    double w[4];
    if (weights)
      for (int i = 0; i < 4; ++i)
        w[i] = weights[ids[i]];
    exactCircumcentreOffset(p[0], p[1], p[2], p[3], offset, weights ? w : nullptr);
    return;
  }
  for (int k = 0; k < 3; ++k)
    offset[k] = (lift[0] * vw[k] + lift[1] * wu[k] + lift[2] * uv[k]).value() / twiceVolume * up;
}

/// ilogb(x) for a finite x > 0, read from its bits where it is normal.
int binaryExponent(double x)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = static_cast<int>(bits >> 52);
  return biased > 0 ? biased - 1023 : std::ilogb(x);
}

/// 2^e for -1022 <= e <= 1023, built from its bits.
double powerOfTwo(int e)
{
  const std::uint64_t bits = std::uint64_t(1023 + e) << 52;
  double x;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

/// Adds to `a` (the first vertex's coordinates) the circumcentre's offset from it, computed on
/// edges scaled by a power of two (exact) to a length near 1, so that their squares and cubes
/// neither underflow nor overflow at any magnitude of the input; in double-double where the
/// tetrahedron is flat enough for doubles to lose the offset's digits.
void addScaledCircumcentre(
  const double* xyz, const double* weights, const std::uint32_t* ids, double* a)
{
  // Below this volume over the product of the edges, the offset in doubles is off by more than
  // 1e-13 of the edges.
  constexpr double kFlat = 1e-3;
  double edges[3][3], longest = 0;
  for (int e = 0; e < 3; ++e)
    for (int k = 0; k < 3; ++k)
    {
      edges[e][k] = xyz[3 * std::size_t(ids[e + 1]) + k] - xyz[3 * std::size_t(ids[0]) + k];
      longest = std::max(longest, std::fabs(edges[e][k]));
    }
  if (!(longest > 0) || !std::isfinite(longest))
    return;
  const int exponent = binaryExponent(longest);
  const bool normal = exponent > -1000 && exponent < 1000; // 2^-exponent is a double
  const double down = normal ? powerOfTwo(-exponent) : 0, up = normal ? powerOfTwo(exponent) : 0;
  for (auto& edge : edges)
    for (double& x : edge)
      x = normal ? x * down : std::ldexp(x, -exponent);
  double lowered[3]; // weighted: the weights' differences, in the edges' scale
  if (weights)
    for (int e = 0; e < 3; ++e)
      lowered[e] = std::ldexp(weights[ids[e + 1]] - weights[ids[0]], -2 * exponent);
  const Circumcentre c =
    circumcentreOfEdges(edges[0], edges[1], edges[2], weights ? lowered : nullptr);
  double offset[3];
  for (int k = 0; k < 3; ++k)
    offset[k] = normal ? c.offset[k] * up : std::ldexp(c.offset[k], exponent);
  if (normal && c.sixVolume * c.sixVolume < kFlat * kFlat * c.edgeProduct2)
    circumcentreInDoubleDouble(xyz, weights, ids, down, up, offset);
  for (int k = 0; k < 3; ++k)
    a[k] += offset[k];
}
} // namespace

void circumcentres(ThreadTeam& team, const double* xyz, const double* weights,
  const IdArray& tetrahedra, const Bounds& box, Doubles& centres, Flags& inBox)
{
  const std::size_t tets = tetrahedra.size() / 4;
  centres.resize(3 * tets);
  inBox.resize(tets);
  team.forRanges(tets, "circumcentres", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
    {
      const std::uint32_t* v = tetrahedra.data() + 4 * t;
      double* x = &centres[3 * t];
      for (int a = 0; a < 3; ++a)
        x[a] = xyz[3 * std::size_t(v[0]) + a];
      addScaledCircumcentre(xyz, weights, v, x);
      inBox[t] = box.contains(x);
    }
  });
}

IdArray numberCentres(ThreadTeam& team, const Flags& inBox)
{
  const std::size_t tets = inBox.size();
  IdArray pointOf(tets + 1);
  std::size_t points = 0;
  team.countThenWrite(
    team.newRecord("voronoi centres"), 0, tets, points,
    [&](std::size_t begin, std::size_t end) {
      return std::size_t(std::count(inBox.begin() + std::ptrdiff_t(begin),
        inBox.begin() + std::ptrdiff_t(end), std::uint8_t(1)));
    },
    [&](std::size_t, std::size_t begin, std::size_t end, std::size_t point) {
      for (std::size_t t = begin; t < end; ++t)
      {
        pointOf[t] = static_cast<std::uint32_t>(point);
        point += inBox[t];
      }
      return point;
    });
  pointOf[tets] = static_cast<std::uint32_t>(points);
  return pointOf;
}

void copyCentres(ThreadTeam& team, std::size_t tets, const Flags& inBox, const IdArray& pointOf,
  const Doubles& centres, VoronoiCells& cells)
{
  team.forRanges(tets, "voronoi centres", [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t)
      if (inBox[t])
        std::copy_n(&centres[3 * t], 3, &cells.points[3 * std::size_t(pointOf[t])]);
  });
}

} // namespace fd3::voronoi
