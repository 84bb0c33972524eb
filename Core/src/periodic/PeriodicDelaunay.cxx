#include "periodic/PeriodicDelaunay.h"

#include "derived/Density.h"
#include "exact/Frame.h"
#include "exact/Predicates.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <stdexcept>

namespace fd3
{
namespace
{
// The farthest a point may lie from the box, in periods, and the widest offset of an image.
constexpr double kMostPeriods = 0x1p30;
constexpr int kMostOffset = 127; // an image's offset in periods, in the output's bytes
// Shells widen by half at least, so that the rounds stay few.
constexpr double kWidening = 1.5;
// Rounds that add the images inside failed spheres only, before the shell widens all round.
constexpr int kTargetedRounds = 6;
// The first shell, in spacings of evenly spread points: wide enough that the certificate holds
// at once for uniform points; a narrower one saves fewer images than a round of regions costs
// (two more passes over the tetrahedra).
constexpr double kFirstShell = 3.0;
// Weighted points reach sqrt(w - w_0) beyond the shell (w_0 the reference weight): at most this
// many periods, beyond which each such point would bring thousands of images.
constexpr double kMostReach = 4.0;
// The reference weight w_0: this quantile of the weights. Lighter points reach no farther than
// the balls, heavier ones their own root beyond; a low one spares the balls of most tetrahedra
// the growth that a heavier reference gives them, and a few outliers, as light as they may be,
// do not make every other point reach far.
constexpr double kReferenceQuantile = 0.05;
// The covering's room beyond the points and the first shell's images, were they spread evenly:
// reserved, untouched memory costs nothing, where every doubling of the lists would copy the
// images' records and fault their pages in again.
constexpr double kCoveringMargin = 1.05;
// Relative slack of the certificate's float evaluation: it only needs to be sufficient, and a
// false failure only widens the shell.
constexpr double kSlack = 1e-6;
// Points per bucket of the lookup of the points in a region.
constexpr std::size_t kPointsPerBucket = 4;
// The lattice that failed spheres' balls are snapped out to, in spacings, where they outnumber
// the points (coarsened()): a coarser one makes fewer regions of more images, a finer one more
// regions.
constexpr double kSnap = 1.0;

/// A tetrahedron's circumsphere in floats, from its vertices' records: the centre is
/// a + n / (2 det), for a = xyz[0] and the differences u of the others from it. Its orthosphere
/// where `lowered` holds the weights of the others less a's: each |u|^2 lowered by its own.
struct SphereTerms
{
  double u[3][3];
  double det; ///< u0 . (u1 x u2)
  double n[3];

  explicit SphereTerms(const double* const xyz[4], const double* lowered = nullptr)
  {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        u[i][k] = xyz[i + 1][k] - xyz[0][k];
    double lift[3], cross[3][3];
    for (int i = 0; i < 3; ++i)
    {
      lift[i] = u[i][0] * u[i][0] + u[i][1] * u[i][1] + u[i][2] * u[i][2];
      if (lowered)
        lift[i] -= lowered[i];
      const double* v = u[(i + 1) % 3];
      const double* w = u[(i + 2) % 3];
      cross[i][0] = v[1] * w[2] - v[2] * w[1];
      cross[i][1] = v[2] * w[0] - v[0] * w[2];
      cross[i][2] = v[0] * w[1] - v[1] * w[0];
    }
    det = u[0][0] * cross[0][0] + u[0][1] * cross[0][1] + u[0][2] * cross[0][2];
    for (int k = 0; k < 3; ++k)
      n[k] = lift[0] * cross[0][k] + lift[1] * cross[1][k] + lift[2] * cross[2][k];
  }

  /// Bounds on the errors of det and of n (its norm, and so each n_k) where every difference is
  /// at most `size` and every record's magnitude at most `most`; usable() says where they hold.
  /// det is a cubic in the differences whose terms sum to 6 size^3 at most, each n_k a quartic
  /// whose terms sum to 18 size^4; each difference is off by eta, its rounding and two residuals,
  /// and each bound is twice the differences' part (degree times eta, taken below size / 100) and
  /// the evaluation's (a few eps a term). Lifts lowered by weights' differences of at most W
  /// stay below 3 s^2 for s^2 = size^2 + W / 3, and their rounding within a few eps of it: n's
  /// bound at that size (weightedSize()) holds them.
  static constexpr double kEps = 0x1p-53;
  static double weightedSize(double size, double spread)
  {
    return spread > 0 ? std::sqrt(size * size + spread / 3) : size;
  }
  static double eta(double size, double most) { return kEps * (size + 2 * most); }
  static bool usable(double size, double most)
  {
    return size > 0x1p-200 && size < 0x1p200 && 100 * eta(size, most) < size;
  }
  static double detError(double size, double most)
  {
    const double s2 = size * size;
    return 2 * (20 * eta(size, most) * s2 + 80 * kEps * s2 * size);
  }
  static double nError(double size, double most)
  {
    const double s2 = size * size;
    return 2 * (130 * eta(size, most) * s2 * size + 520 * kEps * s2 * s2);
  }
};

/// The certificate's first test, which settles nearly every tetrahedron at a point of the box: its
/// circumsphere passes through that point, at least `margin` inside the shell along the periodic
/// axes, so a diameter 2r = |n| / |det| below the margin keeps the sphere inside the shell,
/// compared without a division or a root. Every difference is then below the margin too, which
/// bounds the float evaluation's error (SphereTerms). Weighted, the ball that the certificate
/// checks, about the orthocentre c with the squared radius R^2 = r^2 + w_0 (w_0 the reference
/// weight), has R <= |c - a| + sqrt(max(w_0 - w_a, 0)) (r^2 = |c - a|^2 - w_a), and the point p
/// of the box lies within R + sqrt(max(w_p - w_0, 0)) of c: 2 |c - a| = |n| / |det| must stay
/// below the margin less the largest such root of the vertices and twice a's.
class SmallSphere
{
public:
  /// margin: the points' room to the shell's sides; most: the largest magnitude of a record;
  /// spread: the weights' largest difference, 0 where unweighted.
  SmallSphere(double margin, double most, double spread)
    // The margin less the box's and the records' roundings.
    : margin_(margin - kSlack * (margin + most)), detError_(SphereTerms::detError(margin_, most)),
      nError_(SphereTerms::nError(SphereTerms::weightedSize(margin_, spread), most)),
      usable_(SphereTerms::usable(margin_, most))
  {}

  /// Whether the circumsphere of a tetrahedron with a vertex in the box surely has a diameter
  /// below the margin; weighted, whether its ball surely stays within the margin, for `lowered`
  /// its vertices' weights less the first's and `vertexReach` the largest sqrt(max(w_v - w_0, 0))
  /// of its vertices plus twice sqrt(max(w_0 - w_a, 0)). False where floats cannot tell.
  bool holds(
    const double* const xyz[4], const double* lowered = nullptr, double vertexReach = 0) const
  {
    const double reachAll = margin_ - vertexReach * (1 + kSlack);
    if (!usable_ || !(reachAll > 0))
      return false;
    const SphereTerms t(xyz, lowered);
    bool within = true;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        within &= std::fabs(t.u[i][k]) < margin_;
    const double n2 = t.n[0] * t.n[0] + t.n[1] * t.n[1] + t.n[2] * t.n[2];
    const double reach = reachAll * (std::fabs(t.det) - detError_) - nError_; // |n| stays below
    return within && reach > 0 && n2 * (1 + 1e-12) < reach * reach;
  }

private:
  double margin_, detError_, nError_;
  bool usable_;
};

enum class SphereBox
{
  Made,   ///< the box is made
  Misses, ///< the sphere misses the points' extent (it only touches it)
  Flat    ///< the tetrahedron is too flat for floats to place its sphere
};

/// The circumsphere of a tetrahedron (its vertices' records) where it meets the points' extent
/// along the axes that are not periodic, as a box about it: its reach along the periodic axes
/// (r^2 less the squared gaps to the extent along the others) and its span within the extent
/// along the others, each widened by a bound on the float evaluation's error. The centre, as
/// computed, goes to `centre`, and a radius about it that holds the whole sphere to `radius`.
///
/// The error bounds are SphereTerms', for differences up to the tetrahedron's largest: det's
/// relative error then bounds each coordinate of the centre (a + n / (2 det)) with n's,
/// magnified along the normal of a flat tetrahedron; past a relative error of 1e-3 it is Flat.
/// The gaps and reaches are summed from terms that are never negative (the sphere passes through
/// vertex a, within the extent): r^2 - gap^2 along a free axis k is (a_k - e)(a_k + e - 2 c_k),
/// e the extent's side nearest the centre, and the sphere reaches (r^2 - gap^2) / (r + gap) past
/// that side: a cap far from the centre needs both, r and the gap agreeing to many digits.
///
/// Weighted, the ball about the orthocentre c of squared radius r^2 + w_0, w_0 the reference
/// weight: `lowered` holds the other vertices' weights less a's, and `drop` a's weight less w_0
/// (r^2 = |c - a|^2 - w_a, so the squared radius is |c - a|^2 - drop). It is bounded from above
/// as a whole ball, clipped to the extent along the axes that are not periodic, or where it
/// misses the extent there, the extent's nearest side: a heavy point in the extent may still
/// reach it.
SphereBox sphereBox(const double* const xyz[4], const Bounds& extent, const bool periodic[3],
  double most, double centre[3], double& radius, Bounds& sphere, const double* lowered = nullptr,
  double drop = 0)
{
  const double* a = xyz[0];
  const SphereTerms t(xyz, lowered);
  double size = 0, spread = 0;
  for (int i = 0; i < 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
      size = std::max(size, std::fabs(t.u[i][k]));
    spread = std::max(spread, lowered ? std::fabs(lowered[i]) : 0.0);
  }
  const double det = 2 * t.det;
  const double relative = 2 * SphereTerms::detError(size, most) / std::fabs(det);
  const double nError = SphereTerms::nError(SphereTerms::weightedSize(size, spread), most);
  if (!SphereTerms::usable(size, most) || !(relative < 1e-3))
    return SphereBox::Flat;
  double d[3], r2 = 0; // the centre less a
  for (int k = 0; k < 3; ++k)
  {
    d[k] = t.n[k] / det;
    centre[k] = a[k] + d[k];
    r2 += d[k] * d[k];
  }
  const double r = std::sqrt(r2);
  if (!std::isfinite(r))
    return SphereBox::Flat;
  // How far each of the centre's coordinates may lie from the exact one (a flat tetrahedron's
  // centre is far off along its normal, but not across), and the radius; every other rounding
  // (the sums here, the box's and the extent's bounds in the frame) is within 1e-12 of the
  // magnitudes.
  double error[3], radiusError = 0;
  for (int k = 0; k < 3; ++k)
  {
    error[k] =
      (nError / std::fabs(det) + std::fabs(d[k]) * relative) / (1 - relative) + 1e-12 * (most + r);
    radiusError += error[k];
  }
  // The exact centre and radius each lie within radiusError of these.
  radius = r + 2 * radiusError + 1e-12 * (most + r);
  if (lowered)
  {
    // Weighted: the ball's squared radius |c - a|^2 - drop is below (r + radiusError)^2 less drop
    // as floats round it down.
    const double above = r + radiusError;
    const double lowest = drop * (drop > 0 ? 1 - kSlack : 1 + kSlack);
    const double ball = std::sqrt(std::max(above * above - lowest, 0.0));
    radius = ball + radiusError + 1e-12 * (most + r);
    for (int k = 0; k < 3; ++k)
    {
      sphere.lo[k] = centre[k] - radius;
      sphere.hi[k] = centre[k] + radius;
      if (periodic[k])
        continue;
      sphere.lo[k] = std::min(std::max(sphere.lo[k], extent.lo[k]), extent.hi[k]);
      sphere.hi[k] = std::max(std::min(sphere.hi[k], extent.hi[k]), extent.lo[k]);
    }
    return SphereBox::Made;
  }
  double square[3], squareError[3], gap[3], part[3], partError[3];
  for (int k = 0; k < 3; ++k)
  {
    const double e = centre[k] < extent.lo[k] ? extent.lo[k]
      : centre[k] > extent.hi[k]              ? extent.hi[k]
                                              : centre[k];
    square[k] = d[k] * d[k];
    squareError[k] = (2 * std::fabs(d[k]) + error[k]) * error[k];
    gap[k] = periodic[k] ? 0.0 : std::fabs(centre[k] - e);
    part[k] = gap[k] > 0 ? (a[k] - e) * (a[k] + e - 2 * centre[k]) : square[k];
    partError[k] = gap[k] > 0 ? 2 * std::fabs(a[k] - e) * error[k] : squareError[k];
  }
  double reach2 = 0, reachError = 0;
  for (int k = 0; k < 3; ++k)
  {
    reach2 += part[k];
    reachError += partError[k];
  }
  if (reach2 + reachError <= 0)
    return SphereBox::Misses;
  const double reach = std::sqrt(reach2 + reachError);
  for (int k = 0; k < 3; ++k)
  {
    if (periodic[k])
    {
      sphere.lo[k] = centre[k] - reach - error[k];
      sphere.hi[k] = centre[k] + reach + error[k];
      continue;
    }
    if (gap[k] == 0)
    {
      sphere.lo[k] = std::max(centre[k] - r - radiusError - error[k], extent.lo[k]);
      sphere.hi[k] = std::min(centre[k] + r + radiusError + error[k], extent.hi[k]);
      continue;
    }
    // r^2 - gap_k^2: the other axes' squares and this one's part.
    double within2 = part[k] + partError[k];
    for (int j = 0; j < 3; ++j)
      if (j != k)
        within2 += square[j] + squareError[j];
    within2 = std::max(within2, 0.0);
    const double depth = r > radiusError ? std::min(std::sqrt(within2), within2 / (r - radiusError))
                                         : std::sqrt(within2);
    const double side = centre[k] < extent.lo[k] ? extent.lo[k] : extent.hi[k];
    const double slack = 1e-12 * (most + r);
    sphere.lo[k] = centre[k] < extent.lo[k] ? side : std::max(side - depth - slack, extent.lo[k]);
    sphere.hi[k] = centre[k] < extent.lo[k] ? std::min(side + depth + slack, extent.hi[k]) : side;
  }
  return SphereBox::Made;
}

/// For `points` points whose places span `extent` in `box`: the widest shell (the class
/// documentation's m*) and the spacing of the points, were they spread evenly.
void measure(
  const PeriodicBox& box, std::size_t points, const Bounds& extent, double& widest, double& spacing)
{
  double halfDiagonal = 0, freeDiagonal = 0, volume = 1;
  int dimensions = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = box.periodic[k] ? box.hi[k] - box.lo[k] : extent.extent(k);
    if (box.periodic[k])
      halfDiagonal += 0.25 * e * e;
    else
      freeDiagonal += e * e;
    if (e > 0)
    {
      volume *= e;
      ++dimensions;
    }
  }
  halfDiagonal = std::sqrt(halfDiagonal);
  widest = halfDiagonal + std::sqrt(halfDiagonal * halfDiagonal + freeDiagonal);
  spacing = std::pow(volume / double(std::max<std::size_t>(points, 1)), 1.0 / dimensions);
}

/// Whether the exact value rounded + residual lies below y.
bool below(double rounded, double residual, double y)
{
  return rounded < y || (rounded == y && residual < 0);
}
} // namespace

PeriodicDelaunay::PeriodicDelaunay(const double* xyz, const double* weights, std::size_t count,
  const PeriodicBox& box, const Options& options)
  : xyz_(xyz), weights_(weights), count_(count), own_(count), box_(box), options_(options)
{
  options_.tolerance = 0;
  options_.volumeThreshold = 0;
  options_.computeNeighbors = false; // of the covering, which only gives up its tetrahedra
  for (int k = 0; k < 3; ++k)
  {
    period_[k] = box.hi[k] - box.lo[k];
    if (!box.periodic[k])
      continue;
    if (!(period_[k] > 0) || !std::isfinite(period_[k]) || !std::isfinite(box.lo[k]))
      throw std::invalid_argument("fd3::triangulatePeriodic: a periodic axis with hi <= lo or "
                                  "not finite");
    ++periodicAxes_;
  }
  if (periodicAxes_ == 0)
    throw std::invalid_argument("fd3::triangulatePeriodic: no periodic axis (use triangulate())");
  for (int k = 0; k < 3; ++k)
  {
    region_.lo[k] = box_.periodic[k] ? box_.lo[k] : -HUGE_VAL;
    region_.hi[k] = box_.periodic[k] ? box_.hi[k] : HUGE_VAL;
  }
}

PeriodicDelaunay::PeriodicDelaunay(const double* xyz, std::size_t count, const PeriodicBox& box,
  const Options& options, const PeriodicPiece& piece)
  : PeriodicDelaunay(xyz, nullptr, count, box, options)
{
  if (piece.own > count || (!piece.ids && count > 0) || !(piece.halo > 0))
    throw std::invalid_argument("fd3::PeriodicPiece: more own points than points, no ids or no "
                                "halo");
  own_ = piece.own;
  ids_ = piece.ids;
  region_ = piece.region;
  extent_ = piece.extent;
  piece_ = true;
  pieceHalo_ = piece.halo;
  pieceSetPoints_ = piece.points;
  stars_ = piece.stars;
}

double PeriodicDelaunay::firstShell(
  const PeriodicBox& box, std::size_t points, const Bounds& extent)
{
  double widest, spacing;
  measure(box, points, extent, widest, spacing);
  return std::min(kFirstShell * spacing, widest);
}

bool PeriodicDelaunay::places(std::vector<double>& out)
{
  if (!wrapPoints())
    return false;
  out.assign(3 * count_, std::numeric_limits<double>::quiet_NaN());
  for (const std::uint32_t id : points_)
    std::copy(place_[id].begin(), place_[id].end(), out.begin() + 3 * std::size_t(id));
  return true;
}

bool PeriodicDelaunay::wrapPoints()
{
  place_.resize(count_);
  placeResidual_.resize(count_);
  wraps_.assign(3 * count_, 0);
  representative_.assign(count_, kNoPoint);
  merged_ = false;
  // A coordinate below this bound and not below lo is in the box already, its own place: the
  // bound lies a step below the float sum lo + period, whose rounding the step covers, so that
  // the exact wrap below is left to coordinates that may need one.
  double inside[3];
  for (int k = 0; k < 3; ++k)
    inside[k] = std::nextafter(box_.lo[k] + period_[k], -HUGE_VAL);
  for (std::size_t i = 0; i < count_; ++i)
  {
    const double* p = xyz_ + 3 * i;
    if (!isFinite(p) || (weights_ && !std::isfinite(weights_[i])))
    {
      nonFinite_ += i < own_;
      continue;
    }
    representative_[i] = static_cast<std::uint32_t>(i);
    (i < own_ ? points_ : ghosts_).push_back(static_cast<std::uint32_t>(i));
    for (int k = 0; k < 3; ++k)
    {
      place_[i][k] = p[k];
      placeResidual_[i][k] = 0;
      if (!box_.periodic[k] || (p[k] >= box_.lo[k] && p[k] < inside[k]))
        continue;
      const double periods = std::floor((p[k] - box_.lo[k]) / period_[k]);
      if (!(std::fabs(periods) < kMostPeriods))
        return false;
      // The float quotient may be one off: settle it on the exact places.
      auto wrapped = [&](std::int64_t w, double& rounded, double& residual) {
        return translateExactly(p[k], -w, period_[k], rounded, residual);
      };
      std::int64_t w = static_cast<std::int64_t>(periods);
      double rounded, residual;
      for (int step = 0; step < 4; ++step)
      {
        if (!wrapped(w, rounded, residual))
          return false;
        if (below(rounded, residual, box_.lo[k]))
        {
          --w;
          continue;
        }
        double nextRounded, nextResidual; // one period lower must fall below the box
        if (!wrapped(w + 1, nextRounded, nextResidual))
          return false;
        if (!below(nextRounded, nextResidual, box_.lo[k]))
        {
          ++w;
          continue;
        }
        break;
      }
      place_[i][k] = rounded;
      placeResidual_[i][k] = residual;
      wraps_[3 * i + k] = static_cast<std::int32_t>(w);
    }
  }
  if (weights_)
  {
    std::vector<double> all;
    all.reserve(points_.size() + ghosts_.size());
    forEachPoint([&](std::uint32_t id) { all.push_back(weights_[id]); });
    const auto [lightestAt, heaviestAt] = std::minmax_element(all.begin(), all.end());
    const double lightest = all.empty() ? 0.0 : *lightestAt;
    const double heaviest = all.empty() ? 0.0 : *heaviestAt;
    const auto reference = all.begin() + std::ptrdiff_t(kReferenceQuantile * double(all.size()));
    std::nth_element(all.begin(), reference, all.end());
    referenceWeight_ = all.empty() ? 0.0 : *reference;
    weightSpread_ = heaviest > lightest ? heaviest - lightest : 0;
    farthestReach_ = std::sqrt(std::max(heaviest - referenceWeight_, 0.0));
    if (!(heaviest > lightest))
      weights_ = nullptr;
  }
  return true;
}

void PeriodicDelaunay::chooseFrame()
{
  if (!piece_) // a piece is given the whole set's
  {
    extent_ = Bounds(); // of the places, along every axis
    for (const std::uint32_t id : points_)
      extent_.include(place_[id].data());
  }
  measure(box_, piece_ ? pieceSetPoints_ : points_.size(), extent_, widest_, spacing_);
  coverBounds_ = extent_;
  bool shifts[3] = {true, true, true};
  for (int k = 0; k < 3; ++k)
    if (box_.periodic[k])
    {
      // The widest shell's images and the farthest reach of a weighted point beyond it, a little
      // more for the rounding of their records.
      const double reach = (widest_ + farthestReach_) * (1 + kSlack) + period_[k];
      coverBounds_.lo[k] = box_.lo[k] - reach;
      coverBounds_.hi[k] = box_.lo[k] + period_[k] + reach;
      shifts[k] = false; // images are not among the points checked
    }
  // The cells' clipping box: the widest shell along the periodic axes (no cell of a point of the
  // box reaches it), the box along the others, where it is one, else the points' extent.
  clipBox_ = coverBounds_;
  for (int k = 0; k < 3; ++k)
    if (!box_.periodic[k] && box_.lo[k] < box_.hi[k] && std::isfinite(box_.hi[k] - box_.lo[k]))
    {
      clipBox_.lo[k] = box_.lo[k];
      clipBox_.hi[k] = box_.hi[k];
    }
  Bounds frameBox = coverBounds_;
  const std::vector<double> far = voronoiFarPoints(coverBounds_, clipBox_);
  for (std::size_t i = 0; i < far.size(); i += 3)
    frameBox.include(&far[i]);
  std::vector<double> places;
  places.reserve(3 * (points_.size() + ghosts_.size()));
  forEachPoint(
    [&](std::uint32_t id) { places.insert(places.end(), place_[id].begin(), place_[id].end()); });
  checkShifts(places.data(), places.size() / 3, frameBox, shifts);
  frame_ = frameFor(frameBox, shifts);
  // Every residual must scale exactly too: a multiple of 2^-190 once scaled, as fitsFrame() asks
  // of coordinates (the images' residuals are parts of the places' bits).
  bool fits = fitsFrame(frame_, places.data(), places.size() / 3);
  forEachPoint([&](std::uint32_t id) {
    for (const double r : placeResidual_[id])
    {
      const double y = r * frame_.scale;
      fits =
        fits && (std::fabs(y) >= 0x1p-137 || std::ldexp(y, 190) == std::trunc(std::ldexp(y, 190)));
    }
  });
  if (!fits || (weights_ && !weightsFitFrame(frame_, weights_, count_)))
    frame_ = identityFrame(frameBox);
}

void PeriodicDelaunay::reserveCovering()
{
  // The points spread evenly, and a little more: the shell's images are its share of the volume.
  double share = 1;
  for (int k = 0; k < 3; ++k)
    if (box_.periodic[k])
      share *= 1 + 2 * margin_ / period_[k];
  const auto count = static_cast<std::size_t>(kCoveringMargin * share * double(points_.size()));
  coveringXyz_.reserve(3 * count);
  coveringImages_.reserve(count);
  covering_.reserve(count);
  if (weights_)
    coveringWeights_.reserve(count);
}

void PeriodicDelaunay::addPoints()
{
  for (const std::uint32_t id : points_)
    addImage(id, {0, 0, 0}); // its place, which wrapPoints() found a sum of two doubles
}

bool PeriodicDelaunay::reachesTooFar() const
{
  for (int k = 0; k < 3; ++k)
    if (box_.periodic[k] && farthestReach_ > kMostReach * period_[k])
      return true;
  return false;
}

bool PeriodicDelaunay::inShell(
  std::uint32_t id, const std::array<std::int8_t, 3>& o, double margin) const
{
  if (margin < 0)
    return false;
  margin += reachOf(id);
  for (int k = 0; k < 3; ++k)
  {
    const double x = shifted(id, k, o[k]);
    if (!(x >= region_.lo[k] - margin && x <= region_.hi[k] + margin))
      return false;
  }
  return true;
}

bool PeriodicDelaunay::addImage(std::uint32_t id, const std::array<std::int8_t, 3>& o)
{
  ImageOf image;
  double at[3];
  for (int k = 0; k < 3; ++k)
  {
    image.source[k] = xyz_[3 * id + k];
    image.offset[k] = o[k] - wraps_[3 * id + k];
    if (!translateExactly(image.source[k], image.offset[k], period_[k], at[k], image.residual[k]))
      return false;
  }
  image.key = perturbationKey(image.source, options_.randomSeed);
  coveringXyz_.insert(coveringXyz_.end(), at, at + 3);
  coveringImages_.push_back(image);
  covering_.push_back({id, o});
  if (weights_)
    coveringWeights_.push_back(weights_[id]);
  return true;
}

void PeriodicDelaunay::filePoints()
{
  places_ = Bounds();
  for (const std::uint32_t id : points_)
    places_.include(place_[id].data());
  pointBuckets_ = std::make_unique<Buckets>(places_, points_.size() / kPointsPerBucket + 1);
  for (const std::uint32_t id : points_)
    pointBuckets_->file(id, place_[id].data());
}

bool PeriodicDelaunay::addRegions(const std::vector<ImageRegion>& regions)
{
  if (!pointBuckets_)
    filePoints();
  // The regions of a round overlap, many of them widely (planes across a gap, clusters): a
  // bucket whose points all lie inside a region has its images added at once, and the other
  // regions that hold it pass it over instead of testing each point again.
  std::unordered_set<std::uint64_t> whole;
  const double farthest = farthestReach_;
  for (const ImageRegion& base : regions)
  {
    // Weighted points within their reach of the region: those within the farthest one looked at.
    const ImageRegion region = base.grown(farthest);
    // The periods that bring part of the points' extent into the region, along each axis.
    int first[3], last[3];
    for (int k = 0; k < 3; ++k)
    {
      first[k] = last[k] = 0;
      if (!box_.periodic[k])
        continue;
      const double below = std::floor((region.box.lo[k] - places_.hi[k]) / period_[k]);
      const double above = std::ceil((region.box.hi[k] - places_.lo[k]) / period_[k]);
      if (!(std::max(std::fabs(below), std::fabs(above)) <= kMostOffset))
        return false;
      first[k] = int(below);
      last[k] = int(above);
    }
    for (int x = first[0]; x <= last[0]; ++x)
      for (int y = first[1]; y <= last[1]; ++y)
        for (int z = first[2]; z <= last[2]; ++z)
        {
          const int shift[3] = {x, y, z};
          double back[3]; // the region moved back by the periods
          for (int k = 0; k < 3; ++k)
            back[k] = -shift[k] * period_[k];
          const ImageRegion moved = region.moved(back), movedBase = base.moved(back);
          const std::uint64_t shiftKey = std::uint64_t(std::uint8_t(x)) << 16 |
            std::uint64_t(std::uint8_t(y)) << 8 | std::uint64_t(std::uint8_t(z));
          bool added = true;
          auto take = [&](std::size_t cell, const Bounds& filed,
                        const std::vector<std::uint32_t>& ids) {
            ImageRegion::Overlap overlap =
              ids.empty() ? ImageRegion::Overlap::None : moved.overlap(filed);
            // Within the farthest reach is not within every point's.
            if (farthest > 0 && overlap == ImageRegion::Overlap::All &&
              movedBase.overlap(filed) != ImageRegion::Overlap::All)
              overlap = ImageRegion::Overlap::Some;
            if (overlap == ImageRegion::Overlap::None ||
              (overlap == ImageRegion::Overlap::All &&
                !whole.insert(std::uint64_t(cell) << 24 | shiftKey).second))
              return;
            for (const std::uint32_t id : ids)
              if (added && (overlap == ImageRegion::Overlap::All || inRegion(id, shift, base)))
                added = addRegionImage(id, shift);
          };
          if (moved.radius >= 0)
            pointBuckets_->visitCellsNear(moved.box, moved.centre, moved.radius, take);
          else
            pointBuckets_->visitCells(moved.box, take);
          if (!added)
            return false;
        }
  }
  regions_.insert(regions_.end(), regions.begin(), regions.end());
  return true;
}

bool PeriodicDelaunay::inRegion(std::uint32_t id, const int shift[3], const ImageRegion& base) const
{
  const ImageRegion region = weights_ ? base.grown(reachOf(id)) : base;
  double at[3]; // the image
  for (int k = 0; k < 3; ++k)
  {
    const double x = place_[id][k];
    at[k] = x + shift[k] * period_[k];
    if (!box_.periodic[k])
    {
      if (!(x >= region.box.lo[k] && x <= region.box.hi[k]))
        return false;
      continue;
    }
    // As the offsets that bring the point into the region were found before: in whole periods.
    if (!(std::ceil((region.box.lo[k] - x) / period_[k]) <= shift[k] &&
          shift[k] <= std::floor((region.box.hi[k] - x) / period_[k])))
      return false;
  }
  return region.ballAndSideHold(at);
}

bool PeriodicDelaunay::addRegionImage(std::uint32_t id, const int shift[3])
{
  const std::array<std::int8_t, 3> o = {static_cast<std::int8_t>(shift[0]),
    static_cast<std::int8_t>(shift[1]), static_cast<std::int8_t>(shift[2])};
  if ((o[0] == 0 && o[1] == 0 && o[2] == 0) || inShell(id, o, margin_) ||
    !present_.insert(keyOf(id, o)).second)
    return true;
  return addImage(id, o);
}

bool PeriodicDelaunay::addShell(double inner, double outer)
{
  std::vector<std::int8_t> along[3];
  bool added = true;
  forEachPoint([&](std::uint32_t id) {
    // The offsets along each axis that bring the point into [lo - outer, hi + outer] of the
    // region (the box, or a piece's), the point's reach beyond it added.
    const double reach = outer + reachOf(id);
    for (int k = 0; k < 3; ++k)
    {
      along[k].clear();
      const int most = box_.periodic[k] ? static_cast<int>(std::ceil(reach / period_[k])) + 1 : 0;
      if (most > kMostOffset)
        added = false;
      for (int j = -most; j <= std::min(most, kMostOffset); ++j)
      {
        const double x = shifted(id, k, j);
        if (x >= region_.lo[k] - reach && x <= region_.hi[k] + reach)
          along[k].push_back(static_cast<std::int8_t>(j));
      }
    }
    const bool own = id < own_;
    for (const std::int8_t x : along[0])
      for (const std::int8_t y : along[1])
        for (const std::int8_t z : along[2])
        {
          const std::array<std::int8_t, 3> o = {x, y, z};
          if ((own && x == 0 && y == 0 && z == 0) || inShell(id, o, inner) ||
            present_.count(keyOf(id, o)))
            continue;
          added = added && addImage(id, o);
        }
  });
  return added;
}

bool PeriodicDelaunay::resolveMerged(const Triangulation& covering)
{
  // A covering point that the mesh merged into another has its record: the same image of a point
  // at the same place (a repeat), or an image of a point within a rounding of it (too close).
  bool close = false;
  for (std::size_t c = 0; c < covering_.size(); ++c)
  {
    const std::uint32_t kept = covering.representative[c];
    if (kept == c)
      continue;
    std::uint32_t earlier = covering_[c].owner, later = covering_[kept].owner;
    if (idOf(later) < idOf(earlier))
      std::swap(earlier, later);
    const bool repeat =
      place_[earlier] == place_[later] && placeResidual_[earlier] == placeResidual_[later];
    if (representative_[later] == later && later < own_) // a piece counts its own
      ++(repeat ? duplicates_ : close_);
    representative_[later] = earlier;
    merged_ = true;
    close = close || !repeat;
  }
  for (std::uint32_t& id : representative_)
    if (id != kNoPoint)
      while (representative_[id] != id)
        id = representative_[id];
  for (std::vector<std::uint32_t>* list : {&points_, &ghosts_})
    list->erase(std::remove_if(list->begin(), list->end(),
                  [&](std::uint32_t id) { return representative_[id] != id; }),
      list->end());
  return close;
}

PeriodicDelaunay::Failures PeriodicDelaunay::failures(const IncrementalDelaunay& mesh) const
{
  // In the frame, where the records are: the box, the region the shell is about, the regions and
  // the points' extent along the axes that are not periodic.
  const Bounds extent = toFrame(frame_, extent_);
  Bounds box;
  std::copy(box_.lo, box_.lo + 3, box.lo);
  std::copy(box_.hi, box_.hi + 3, box.hi);
  box = toFrame(frame_, box);
  const Bounds around = toFrame(frame_, region_);
  const double scale = frame_.identity ? 1.0 : frame_.scale;
  std::vector<ImageRegion> regions;
  Bounds all;
  for (const ImageRegion& region : regions_)
  {
    // A hull face's region, on the face's outer side, holds none of the spheres through the
    // face: it only brings images in (outerBall()).
    if (region.sided())
      continue;
    ImageRegion r = region;
    r.box = toFrame(frame_, region.box);
    for (int k = 0; k < 3; ++k)
      r.centre[k] = toFrame(frame_, region.centre[k], k);
    r.radius *= scale;
    regions.push_back(r);
    all.include(r.box);
  }
  Buckets regionBuckets(all, regions.size());
  for (std::size_t r = 0; r < regions.size(); ++r)
    regionBuckets.file(std::uint32_t(r), regions[r].box);
  const double margin = margin_ * scale, spacing = spacing_ * scale;
  double most = 0; // the largest magnitude of a record
  for (int k = 0; k < 3; ++k)
    most = std::max({most, std::fabs(toFrame(frame_, coverBounds_.lo[k], k)),
      std::fabs(toFrame(frame_, coverBounds_.hi[k], k))});
  // Weighted: in the frame, whose scale squares in the weights (the mesh's are in it).
  const double weightScale = scale * scale, reference = referenceWeight_ * weightScale;
  const SmallSphere small(margin, most, weightSpread_ * weightScale);
  Failures out;
  std::mutex failed; // rare, from every thread of the visit
  auto fail = [&](ImageRegion region, std::vector<ImageRegion>& list) {
    // Within the widest shell, beyond which no image is needed: a sphere that reaches farther
    // belongs to a tetrahedron that the images within it will take apart.
    for (int k = 0; k < 3; ++k)
    {
      region.box.lo[k] = fromFrame(frame_, region.box.lo[k], k);
      region.box.hi[k] = fromFrame(frame_, region.box.hi[k], k);
      region.centre[k] = fromFrame(frame_, region.centre[k], k);
      if (box_.periodic[k])
      {
        region.box.lo[k] = std::max(region.box.lo[k], box_.lo[k] - widest_);
        region.box.hi[k] = std::min(region.box.hi[k], box_.hi[k] + widest_);
      }
    }
    region.radius /= scale;
    const std::lock_guard<std::mutex> lock(failed);
    list.push_back(region);
  };
  // A hull face of the covering that a point of the box is on must be one of the repeated set's:
  // across the periodic axes, its half-space would take in images (with every axis periodic it
  // has none). What it lacks are images of the points on its outer side, within a period of it.
  mesh.visitHullFaces([&](const std::uint32_t face[3], const double* const xyz[3]) {
    if (std::min({face[0], face[1], face[2]}) >= boxPoints_ || parallelToPeriods(face))
      return;
    if (periodicAxes_ == 3)
    {
      std::array<double, 9> corners;
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
          corners[3 * i + k] = fromFrame(frame_, xyz[i][k], k);
      const std::lock_guard<std::mutex> lock(failed);
      out.outerFaces.push_back(corners);
      return;
    }
    Bounds region;
    for (int i = 0; i < 3; ++i)
      region.include(xyz[i]);
    const double *a = xyz[0], *b = xyz[1], *c = xyz[2];
    for (int k = 0; k < 3; ++k)
    {
      if (box_.periodic[k])
      {
        const double period = box.hi[k] - box.lo[k];
        region.lo[k] -= period;
        region.hi[k] += period;
        continue;
      }
      // The normal's component along k (its sign picks the outer side).
      const int u = (k + 1) % 3, v = (k + 2) % 3;
      const double normal = (b[u] - a[u]) * (c[v] - a[v]) - (b[v] - a[v]) * (c[u] - a[u]);
      if (normal > 0)
        region.hi[k] = extent.hi[k];
      else
        region.lo[k] = extent.lo[k];
    }
    fail({region}, out.hull);
  });
  mesh.visitTetrahedra([&](const std::uint32_t ids[4], const double* const xyz[4],
                         const double* weights) {
    if (std::min({ids[0], ids[1], ids[2], ids[3]}) >= boxPoints_)
      return;
    double lowered[3], drop = 0, reach = 0;
    if (weights)
    {
      double heaviest = weights[0];
      for (int i = 0; i < 3; ++i)
      {
        lowered[i] = weights[i + 1] - weights[0];
        heaviest = std::max(heaviest, weights[i + 1]);
      }
      drop = weights[0] - reference;
      // The box's point's reach, and twice what a's lightness adds to the ball (SmallSphere).
      reach = std::sqrt(std::max(heaviest - reference, 0.0)) + 2 * std::sqrt(std::max(-drop, 0.0));
    }
    const double* lowers = weights ? lowered : nullptr;
    if (small.holds(xyz, lowers, reach))
      return;
    double c[3], radius;
    Bounds sphere;
    const SphereBox made =
      sphereBox(xyz, extent, box_.periodic, most, c, radius, sphere, lowers, drop);
    if (made == SphereBox::Misses)
      return;
    if (made == SphereBox::Flat)
    {
      // Flat in floats: the images within half a period of it.
      Bounds around;
      for (int i = 0; i < 4; ++i)
        around.include(xyz[i]);
      for (int k = 0; k < 3; ++k)
      {
        const double grow = box_.periodic[k] ? 0.5 * (box.hi[k] - box.lo[k]) : spacing;
        around.lo[k] -= grow;
        around.hi[k] += grow;
      }
      fail({around}, out.spheres);
      return;
    }
    bool inShell = true;
    for (int k = 0; k < 3; ++k)
      inShell =
        inShell && sphere.lo[k] > around.lo[k] - margin && sphere.hi[k] < around.hi[k] + margin;
    if (inShell)
      return;
    // A region that holds the sphere holds its centre, and is filed where the centre is.
    bool inRegion = false;
    Bounds centre;
    centre.include(c);
    regionBuckets.visit(centre, [&](std::uint32_t r) {
      if (inRegion)
        return;
      inRegion = regions[r].holds(sphere, c, radius, most);
    });
    if (inRegion)
      return;
    // A region a spacing wider, so that the tetrahedra that replace this one fit it too; its
    // ball where every axis is periodic.
    ImageRegion failure{sphere};
    for (int k = 0; k < 3; ++k)
    {
      failure.box.lo[k] -= spacing;
      failure.box.hi[k] += spacing;
      failure.centre[k] = c[k];
    }
    if (periodicAxes_ == 3)
      failure.radius = radius + spacing;
    fail(failure, out.spheres);
  });
  return out;
}

double PeriodicDelaunay::widerHaloFor(const Failures& failed) const
{
  if (failed.hull.empty() && failed.spheres.empty() && failed.outerFaces.empty())
    return 0;
  double halo = kWidening * margin_;
  for (const ImageRegion& sphere : failed.spheres)
    for (int k = 0; k < 3; ++k)
      halo = std::max({halo, region_.lo[k] - sphere.box.lo[k], sphere.box.hi[k] - region_.hi[k]});
  return std::min(halo, widest_);
}

std::vector<ImageRegion> PeriodicDelaunay::coarsened(const std::vector<ImageRegion>& regions) const
{
  if (regions.size() <= points_.size())
    return regions;
  const double step = kSnap * spacing_;
  std::vector<std::pair<std::array<std::int64_t, 4>, ImageRegion>> balls;
  std::vector<ImageRegion> out;
  for (const ImageRegion& region : regions)
  {
    std::array<std::int64_t, 4> key;
    ImageRegion snapped;
    double apart = 0; // the centre's move, squared
    for (int k = 0; k < 3; ++k)
    {
      const double node = std::round(region.centre[k] / step);
      key[k] = std::int64_t(node);
      snapped.centre[k] = node * step;
      apart += (snapped.centre[k] - region.centre[k]) * (snapped.centre[k] - region.centre[k]);
    }
    const double steps = std::ceil((region.radius + std::sqrt(apart)) / step) + 1; // and roundings
    if (region.radius < 0 || region.sided() || !(steps < 0x1p52) ||
      !std::isfinite(apart + snapped.centre[0] + snapped.centre[1] + snapped.centre[2]))
    {
      out.push_back(region);
      continue;
    }
    key[3] = std::int64_t(steps);
    snapped.radius = steps * step;
    for (int k = 0; k < 3; ++k)
    {
      snapped.box.lo[k] = std::max(snapped.centre[k] - snapped.radius, box_.lo[k] - widest_);
      snapped.box.hi[k] = std::min(snapped.centre[k] + snapped.radius, box_.hi[k] + widest_);
    }
    balls.emplace_back(key, snapped);
  }
  std::sort(
    balls.begin(), balls.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < balls.size(); ++i)
    if (i == 0 || balls[i].first != balls[i - 1].first)
      out.push_back(balls[i].second);
  return out;
}

ImageRegion PeriodicDelaunay::outerBall(const std::array<double, 9>& face)
{
  const double *a = &face[0], *b = &face[3], *c = &face[6];
  // The face's circle: its centre o, its squared radius, and the unit normal outwards.
  double u[3], v[3], w[3], uu = 0, vv = 0, ww = 0;
  for (int k = 0; k < 3; ++k)
  {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    uu += u[k] * u[k];
    vv += v[k] * v[k];
  }
  for (int k = 0; k < 3; ++k)
  {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    w[k] = u[i] * v[j] - u[j] * v[i];
    ww += w[k] * w[k];
  }
  const double m[3] = {uu * v[0] - vv * u[0], uu * v[1] - vv * u[1], uu * v[2] - vv * u[2]};
  double o[3], rho2 = 0, normal[3];
  for (int k = 0; k < 3; ++k)
  {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    o[k] = a[k] + (m[i] * w[j] - m[j] * w[i]) / (2 * ww);
    rho2 += (o[k] - a[k]) * (o[k] - a[k]);
    normal[k] = w[k] / std::sqrt(ww);
  }
  // The sphere through the circle and q has its centre at o + t normal.
  double least = HUGE_VAL;
  auto consider = [&](const double q[3]) {
    double height = 0, d2 = 0;
    for (int k = 0; k < 3; ++k)
    {
      height += (q[k] - o[k]) * normal[k];
      d2 += (q[k] - o[k]) * (q[k] - o[k]);
    }
    if (height > 0)
      least = std::min(least, (d2 - rho2) / (2 * height));
  };
  if (!pointBuckets_)
    filePoints();
  const double rho = std::sqrt(rho2);
  for (int axis = 0; axis < 3; ++axis)
  {
    if (!(normal[axis] != 0))
      continue;
    const double step = std::copysign(period_[axis], normal[axis]);
    for (const double* vertex : {a, b, c})
    {
      double q[3] = {vertex[0], vertex[1], vertex[2]};
      q[axis] += step;
      consider(q);
    }
    Bounds across = places_; // the points whose places lie across the circle along the axis
    for (int k = 0; k < 3; ++k)
      if (k != axis)
      {
        across.lo[k] = std::max(across.lo[k], o[k] - rho);
        across.hi[k] = std::min(across.hi[k], o[k] + rho);
      }
    if (across.empty())
      continue;
    pointBuckets_->visit(across, [&](std::uint32_t id) {
      double q[3] = {place_[id][0], place_[id][1], place_[id][2]};
      q[axis] += step;
      consider(q);
    });
  }
  ImageRegion region;
  if (!std::isfinite(least)) // a face too flat for floats: a period about it
  {
    for (int k = 0; k < 3; ++k)
    {
      region.box.lo[k] = std::min({a[k], b[k], c[k]}) - period_[k];
      region.box.hi[k] = std::max({a[k], b[k], c[k]}) + period_[k];
    }
    return region;
  }
  // The outer cap of that sphere; with its centre below the circle's plane (t < 0) it lies
  // within the circle's own ball, which bounds it, and is thin where t is far below.
  const double t = std::isfinite(std::sqrt(rho2 + least * least)) ? least : 0.0;
  region.radius = std::sqrt(rho2 + t * t) + spacing_;
  const double reach = t < 0 ? rho + spacing_ : region.radius;
  for (int k = 0; k < 3; ++k)
  {
    region.centre[k] = o[k] + t * normal[k];
    region.normal[k] = normal[k];
    region.onPlane[k] = a[k];
    const double middle = t < 0 ? o[k] : region.centre[k];
    region.box.lo[k] = std::max(middle - reach, box_.lo[k] - widest_);
    region.box.hi[k] = std::min(middle + reach, box_.hi[k] + widest_);
  }
  return region;
}

bool PeriodicDelaunay::parallelToPeriods(const std::uint32_t face[3]) const
{
  if (periodicAxes_ == 3)
    return false;
  // The normal's component along axis k vanishes where the face's projection across k is a
  // segment: three collinear points, decided exactly on the images.
  for (int k = 0; k < 3; ++k)
  {
    if (!box_.periodic[k])
      continue;
    double projected[3][3];
    PeriodicImages images;
    for (int i = 0; i < 3; ++i)
    {
      ImageOf image = coveringImages_[face[i]];
      for (int a = 0; a < 3; ++a)
        projected[i][a] = a == k ? 0.0 : coveringXyz_[3 * face[i] + a];
      image.residual[k] = 0;
      images.append(image);
    }
    images.locate(projected[0], 3);
    Predicates predicates;
    predicates.useImages(&images);
    if (!predicates.collinear(projected[0], projected[1], projected[2]))
      return false;
  }
  return true;
}

bool PeriodicDelaunay::extractStars(const Triangulation& covering, PeriodicTriangulation& out)
{
  // A tetrahedron by its vertices' ranks once its least vertex is moved to offset 0: the same for
  // every copy.
  using Key = std::array<std::uint64_t, 4>;
  struct KeyHash
  {
    std::size_t operator()(const Key& key) const
    {
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (const std::uint64_t x : key)
        h = (h ^ x) * 0x100000001B3ull;
      return std::size_t(h ^ (h >> 31));
    }
  };
  std::unordered_set<Key, KeyHash> seen;
  out.tetrahedra.clear();
  out.offsets.clear();
  owned_.clear();
  for (std::size_t t = 0; t < covering.numberOfTetrahedra(); ++t)
  {
    const std::uint32_t* v = &covering.tetrahedra[4 * t];
    if (std::min({v[0], v[1], v[2], v[3]}) >= boxPoints_)
      continue;
    const int least = leastVertex(v);
    CoveringPoint moved[4];
    Key key;
    for (int i = 0; i < 4; ++i)
    {
      moved[i] = covering_[v[i]];
      for (int k = 0; k < 3; ++k)
      {
        const int o = moved[i].offset[k] - covering_[v[least]].offset[k];
        if (std::abs(o) > kMostOffset)
          return false;
        moved[i].offset[k] = static_cast<std::int8_t>(o);
      }
      key[i] = rankOf(moved[i]);
    }
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second)
      continue;
    for (const CoveringPoint& p : moved)
    {
      out.tetrahedra.push_back(representative_[p.owner]);
      out.offsets.insert(out.offsets.end(), p.offset.begin(), p.offset.end());
    }
    owned_.push_back(representative_[moved[least].owner] < own_);
  }
  return true;
}

void PeriodicDelaunay::extract(const Triangulation& covering, PeriodicTriangulation& out) const
{
  // The copy of each tetrahedron whose least vertex is in the box: as many as the box's points
  // have tetrahedra, fewer than the covering's. Most have only points of the box, each its own
  // representative where every input point is one (its covering id is then its input id): those
  // are written with no lookup by id, whose order is the input's, not space's.
  const std::size_t n = covering.numberOfTetrahedra();
  const bool ownIds = points_.size() == own_;
  out.tetrahedra.resize(4 * n);
  out.offsets.resize(12 * n); // zero: the box's points
  std::uint32_t* ids = out.tetrahedra.data();
  std::int8_t* offsets = out.offsets.data();
  for (std::size_t t = 0; t < n; ++t)
  {
    const std::uint32_t* v = &covering.tetrahedra[4 * t];
    const std::uint32_t highest = std::max({v[0], v[1], v[2], v[3]});
    if (ownIds && highest < boxPoints_)
    {
      ids = std::copy_n(v, 4, ids);
      offsets += 12;
      continue;
    }
    if (std::min({v[0], v[1], v[2], v[3]}) >= boxPoints_)
      continue;
    const int least = leastVertex(v);
    const CoveringPoint& first = covering_[v[least]];
    if (first.offset != std::array<std::int8_t, 3>{0, 0, 0} ||
      representative_[first.owner] >= own_) // a piece's ghost
      continue;
    for (int i = 0; i < 4; ++i)
    {
      const CoveringPoint& p = covering_[v[i]];
      *ids++ = representative_[p.owner]; // the first of repeats
      offsets = std::copy(p.offset.begin(), p.offset.end(), offsets);
    }
  }
  out.tetrahedra.resize(std::size_t(ids - out.tetrahedra.data()));
  out.offsets.resize(std::size_t(offsets - out.offsets.data()));
}

std::vector<std::uint32_t> PeriodicDelaunay::hiddenOfBox(const Triangulation& covering) const
{
  std::vector<std::uint32_t> out;
  for (const std::uint32_t c : covering.hidden)
    if (c < boxPoints_)
      out.push_back(covering_[c].owner);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<double> PeriodicDelaunay::densitiesOfBoxPoints(const Triangulation& covering) const
{
  if (covering.status != Status::Ok)
    return std::vector<double>(own_, std::numeric_limits<double>::quiet_NaN());
  std::vector<std::uint32_t> source(covering_.size(), std::uint32_t(own_));
  for (std::uint32_t c = 0; c < boxPoints_; ++c)
    source[c] = representative_[covering_[c].owner];
  return densitiesOfCorners(
    own_, covering.tetrahedra, coveringXyz_.data(), source.data(), representative_.data());
}

std::unique_ptr<IncrementalDelaunay> PeriodicDelaunay::cover(PeriodicTriangulation& out)
{
  coveringXyz_.clear();
  coveringImages_.clear();
  coveringWeights_.clear();
  covering_.clear();
  regions_.clear();
  present_.clear();
  out.rounds = 0;
  widerHalo_ = 0;
  margin_ = std::min(piece_ ? pieceHalo_ : kFirstShell * spacing_, widest_);
  pointBuckets_.reset(); // the points may have changed: filed again when a region asks
  reserveCovering();
  addPoints(); // first, the cells' generators
  boxPoints_ = static_cast<std::uint32_t>(covering_.size());
  if (!addShell(-1, margin_))
    return nullptr;
  auto mesh = IncrementalDelaunay::ofImages(Coordinates(coveringXyz_.begin(), coveringXyz_.end()),
    coveringImages_.data(), options_, frame_, weights_ ? coveringWeights_.data() : nullptr);
  if (piece_ && margin_ < widest_) // the other pieces send a wider halo where this one falls short
  {
    const Status status = mesh->status();
    if (status == Status::Ok)
      widerHalo_ = widerHaloFor(failures(*mesh));
    else if (status == Status::TooFewPoints || status == Status::Degenerate)
      widerHalo_ = widest_; // flat here, as a slab's plane far from its other points
  }
  if (piece_)
    return mesh;
  std::size_t inserted = covering_.size();
  for (int targeted = 0; mesh->status() == Status::Ok && margin_ < widest_;)
  {
    Failures failed = failures(*mesh);
    // Weighted, the hull faces' regions would need the orthospheres through them: a wider shell.
    const bool outerFaces = !failed.outerFaces.empty();
    if (!weights_)
      for (const std::array<double, 9>& face : failed.outerFaces)
        failed.hull.push_back(outerBall(face));
    if (failed.hull.empty() && failed.spheres.empty() && !outerFaces)
      break;
    // The images inside the failed regions, a few times; then a wider shell all round. A slab's
    // hull first: where the images of its highest and lowest points are missing, the spheres
    // under it are wrong too, and would ask for far more.
    if (targeted < kTargetedRounds && !(weights_ && outerFaces))
    {
      ++targeted;
      if (!addRegions(failed.hull.empty() ? coarsened(failed.spheres) : failed.hull))
        return nullptr;
    }
    else
    {
      const double wider = std::min(kWidening * margin_, widest_);
      if (!addShell(margin_, wider))
        return nullptr;
      margin_ = wider;
    }
    ++out.rounds;
    if (covering_.size() > inserted)
      mesh->addImages(&coveringXyz_[3 * inserted], &coveringImages_[inserted],
        covering_.size() - inserted, weights_ ? &coveringWeights_[inserted] : nullptr);
    inserted = covering_.size();
  }
  return mesh;
}

Status PeriodicDelaunay::prepare(Statistics& stats)
{
  stats.inputPoints = own_;
  if (!wrapPoints() || reachesTooFar())
    return Status::OutOfRange;
  stats.nonFinitePoints = nonFinite_;
  if (points_.empty())
    return Status::Empty;
  chooseFrame();
  return Status::Ok;
}

void PeriodicDelaunay::countPoints(Statistics& stats) const
{
  stats.inputPoints = own_;
  stats.nonFinitePoints = nonFinite_;
  stats.duplicatesMerged = duplicates_;
  stats.closePointsSkipped = close_;
  stats.insertedPoints = points_.size();
}

PeriodicTriangulation PeriodicDelaunay::run(std::vector<double>* density)
{
  const auto start = std::chrono::steady_clock::now();
  PeriodicTriangulation out;
  out.status = prepare(out.stats);
  if (out.status != Status::Ok)
    return out;
  Triangulation covering;
  for (bool again = true; again;)
  {
    const std::unique_ptr<IncrementalDelaunay> mesh = cover(out);
    if (!mesh)
    {
      out.status = Status::OutOfRange;
      return out;
    }
    // A piece's certificate fails on the flat tetrahedra of points within a rounding of each
    // other too: it stands once they are resolved.
    if (widerHalo_ > 0 && mesh->mergedPoints() == 0)
      return out;
    covering = mesh->release();
    // Rare: points within a rounding of each other, whose images' records coincide.
    again = covering.status == Status::Ok && resolveMerged(covering);
    if (!again && widerHalo_ > 0)
      return out;
  }
  out.status = covering.status;
  out.stats = covering.stats;
  countPoints(out.stats);
  out.hidden = hiddenOfBox(covering);
  out.stats.hiddenPoints = out.hidden.size();
  out.stats.insertedPoints -= out.hidden.size();
  out.imagePoints = covering_.size() - boxPoints_;
  out.margin = margin_;
  if (out.status == Status::Ok && !stars_)
    extract(covering, out);
  if (out.status == Status::Ok && stars_ && !extractStars(covering, out))
    out.status = Status::OutOfRange;
  if (density)
    *density = densitiesOfBoxPoints(covering);
  out.stats.tetrahedra = stars_
    ? std::size_t(std::count(owned_.begin(), owned_.end(), std::uint8_t(1)))
    : out.numberOfTetrahedra();
  out.stats.secondsTotal =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.wraps = wraps_;
  out.representative.assign(representative_.begin(), representative_.end());
  return out;
}

VoronoiCells PeriodicDelaunay::cells(const VoronoiOptions& options)
{
  VoronoiCells out;
  out.cellFaces.assign(1, 0);
  out.faceStart.assign(1, 0);
  out.cellPointStart.assign(1, 0);
  options_.threads = options.threads;
  options_.progress = options.progress;
  out.status = prepare(out.stats);
  if (out.status != Status::Ok)
    return out;
  PeriodicTriangulation run;
  std::unique_ptr<IncrementalDelaunay> mesh;
  while (!mesh)
  {
    mesh = cover(run);
    if (!mesh)
    {
      out.status = Status::OutOfRange;
      return out;
    }
    if (mesh->status() == Status::Ok && mesh->mergedPoints() > 0)
    {
      // Repeats, or points too close: without them, none are merged.
      resolveMerged(mesh->release());
      mesh.reset();
    }
  }
  if (widerHalo_ > 0)
    return out;
  VoronoiOptions own = options;
  own.box = clipBox_;
  own.generators = points_.size(); // the covering's first points
  Coordinates xyz;
  out = voronoiCells(*mesh, coverBounds_, own, xyz, weights_ ? coveringWeights_.data() : nullptr);
  // From the covering's points to the input's, through one table: the neighbours come in no
  // order of either.
  std::vector<std::uint32_t> inputOf(covering_.size());
  for (std::size_t c = 0; c < covering_.size(); ++c)
    inputOf[c] = representative_[covering_[c].owner];
  for (std::uint32_t& g : out.generators)
    g = inputOf[g];
  for (std::uint32_t& n : out.faceNeighbors)
    if (n < kBoxFace)
      n = inputOf[n];
  out.box = clipBox_;
  countPoints(out.stats);
  out.stats.insertedPoints -= out.stats.hiddenPoints; // voronoiCells() counted the generators'
  return out;
}

VoronoiCells voronoiCellsPeriodic(
  const double* xyz, std::size_t count, const PeriodicBox& box, const VoronoiOptions& options)
{
  return voronoiCellsPeriodic(xyz, nullptr, count, box, options);
}

VoronoiCells voronoiCellsPeriodic(const double* xyz, const double* weights, std::size_t count,
  const PeriodicBox& box, const VoronoiOptions& options)
{
  return PeriodicDelaunay(xyz, weights, count, box, Options()).cells(options);
}

PeriodicTriangulation triangulatePeriodic(
  const double* xyz, std::size_t count, const PeriodicBox& box, const Options& options)
{
  return triangulatePeriodic(xyz, nullptr, count, box, options);
}

PeriodicTriangulation triangulatePeriodic(const double* xyz, const double* weights,
  std::size_t count, const PeriodicBox& box, const Options& options)
{
  return PeriodicDelaunay(xyz, weights, count, box, options).run();
}

bool periodicPlaces(
  const double* xyz, std::size_t count, const PeriodicBox& box, std::vector<double>& places)
{
  return PeriodicDelaunay(xyz, nullptr, count, box, Options()).places(places);
}

bool periodicImageWithin(
  const double place[3], const PeriodicBox& box, const Bounds& region, double halo)
{
  for (int k = 0; k < 3; ++k)
  {
    // Widened by more than the roundings of places, periods and bounds.
    const double slack =
      kSlack * (std::fabs(place[k]) + std::fabs(region.lo[k]) + std::fabs(region.hi[k]) + halo);
    const double lo = region.lo[k] - halo - slack, hi = region.hi[k] + halo + slack;
    if (!box.periodic[k])
    {
      if (!(place[k] >= lo && place[k] <= hi))
        return false;
      continue;
    }
    // The image first above lo, or one a period either side where the quotient rounds off.
    const double period = box.hi[k] - box.lo[k];
    const double first = std::ceil((lo - place[k]) / period);
    bool any = false;
    for (const double periods : {first - 1, first, first + 1})
    {
      const double x = place[k] + periods * period;
      any = any || (x >= lo && x <= hi);
    }
    if (!any)
      return false;
  }
  return true;
}

double firstPeriodicHalo(const PeriodicBox& box, std::size_t points, const Bounds& extent)
{
  return PeriodicDelaunay::firstShell(box, points, extent);
}

PeriodicPieceTriangulation triangulatePeriodicPiece(const double* xyz, std::size_t count,
  const PeriodicBox& box, const PeriodicPiece& piece, bool density, const Options& options)
{
  PeriodicDelaunay run(xyz, count, box, options, piece);
  PeriodicPieceTriangulation out;
  out.triangulation = run.run(density ? &out.density : nullptr);
  out.widerHalo = run.widerHalo();
  out.owned = std::move(run.owned());
  return out;
}

VoronoiCells voronoiCellsPeriodicPiece(const double* xyz, std::size_t count, const PeriodicBox& box,
  const PeriodicPiece& piece, double& widerHalo, const VoronoiOptions& options)
{
  PeriodicDelaunay run(xyz, count, box, Options(), piece);
  VoronoiCells out = run.cells(options);
  widerHalo = run.widerHalo();
  return out;
}

} // namespace fd3
