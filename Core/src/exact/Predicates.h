// Geometric predicates of the kernel, in layers: a floating-point evaluation with a rigorous error
// bound (decides almost every call), then, for insphere, a double-double evaluation with its own
// bound (decides the near-degenerate cases that thin tetrahedra on surface samples make in
// numbers), then exact arithmetic. The float layer is inline here because it runs tens of times
// per insertion inside the cavity search; the others are rare and live in Predicates.cxx.
// Signs follow VTK's tetrahedron convention:
//   orient3d(a,b,c,d) > 0  iff  (b-a) x (c-a) . (d-a) > 0,
//   inSphere(a,b,c,d,e) > 0 iff e lies strictly inside the circumsphere of the positive tet abcd.
// The kernel computes in a frame that scales the points exactly into [-1, 1] where one exists, so
// that no product of five coordinate differences overflows or underflows. Points no such frame
// holds exactly stay as they are, and allowAnyMagnitude() then guards every filter against
// overflow and underflow and moves the exact stage to integers of unbounded size.
#ifndef fd3_Predicates_h
#define fd3_Predicates_h

#include "exact/DoubleDouble.h"
#include "exact/Expansion.h"
#include "exact/PeriodicImages.h"
#include "fd3/Bounds.h"
#include "system/Platform.h"

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace fd3
{

/// |(b - a) x (c - a) . (d - a)|, six times the tetrahedron's volume, as mantissa * 2^exponent
/// (mantissa in [0.5, 1), or 0), computed exactly from any finite coordinates and rounded once.
void exactSixVolume(const double* a, const double* b, const double* c, const double* d,
  double& mantissa, int& exponent);

/// The circumcentre of tetrahedron abcd less a, computed exactly from any finite coordinates and
/// rounded once per coordinate to within a few units in the last place; false, with `offset`
/// unchanged, where the four points are coplanar. With `weights` (of a, b, c, d), the orthocentre
/// of the weighted points instead.
bool exactCircumcentreOffset(const double* a, const double* b, const double* c, const double* d,
  double offset[3], const double* weights = nullptr);

/// A point's key in the symbolic perturbation's order, from its (normalized) coordinates alone and
/// the seed: every run computes the same key for the same point, whatever the other points, the
/// insertion order, the threads or the MPI ranks (which share one frame). Its top 4 bits are 15
/// minus the point's BRIO level (a level-k point is one in 2^(k+1), the levels' rounds going in
/// from the highest), so that the first point of any set in the perturbation's order is inserted
/// among the first. Inline: a loop over the points hoists the seed's mix out of it.
inline std::uint16_t perturbationKey(const double* p, std::uint64_t seed)
{
  // splitmix64's finalizer over the coordinates' bits (-0 as 0: the same point).
  auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  std::uint64_t hash = mix(seed + 0x9E3779B97F4A7C15ull);
  for (int a = 0; a < 3; ++a)
  {
    std::uint64_t bits;
    const double x = p[a] == 0.0 ? 0.0 : p[a];
    std::memcpy(&bits, &x, sizeof bits);
    hash = mix(hash ^ bits);
  }
  const int level = std::min(countTrailingZeros(hash | (1ull << 63)), 15);
  return static_cast<std::uint16_t>(((15 - level) << 12) | ((hash >> 48) & 0xFFFu));
}

/// The perturbation's order of points: by key, then by coordinates, so that distinct points are
/// never tied.
inline bool precedes(std::uint16_t keyA, const double* a, std::uint16_t keyB, const double* b)
{
  if (keyA != keyB)
    return keyA < keyB;
  return std::lexicographical_compare(a, a + 3, b, b + 3);
}

namespace filter
{
constexpr double kEpsilon = DBL_EPSILON / 2; // unit roundoff 2^-53
// Error bounds of the float evaluations below: Shewchuk's (1997) relative bounds, for differences
// of inputs, times a bound on the permanent from the largest differences; 2% covers the rounding
// of that product of maxima.
constexpr double kOrientSemiStatic = 1.02 * 6 * (7.0 + 56.0 * kEpsilon) * kEpsilon;
constexpr double kInSphereSemiStatic = 1.02 * 72 * (16.0 + 224.0 * kEpsilon) * kEpsilon;
// The power test (Predicates::powerTest()): each lift |x - e|^2 - (w_x - w_e) is at most
// 3 m^2 + max |w_x - w_e| and each 3x3 permanent at most 6 mx my mz, so the permanent of the
// determinant is at most 24 mx my mz (3 m^2 + max |dw|). Counted to first order, the evaluation's
// error is below 17 u times the permanent (a 3x3 minor 8 u, a lift 6 u, their product u more, the
// sum 2 u); 24 u leaves room for the higher orders, 5% for the rounding of the bound.
constexpr double kPowerSemiStatic = 1.05 * 24 * 24 * kEpsilon;
// 2D incircle on the permanent itself, computed from the same rounded differences (5% for the
// rounding of the permanent).
constexpr double kInCircle = 1.05 * (10.0 + 96.0 * kEpsilon) * kEpsilon;
// The lifts' filter: the permanent of insphere is sum_r L_r Q_r, L_r the lifts |r - e|^2 and
// Q_r the permanent of the absolute 3x3 minor of the other rows; a nonnegative permanent is at most
// the product of its row sums, each at most sqrt(3) times its row's length sqrt(L), so
// permanent <= 3 sqrt(3) sqrt(prod L) sum_r sqrt(L_r), and by Cauchy-Schwarz
// permanent^2 <= 108 prod L sum L. Squared, with Shewchuk's (16 + 224 eps) eps and 5% for the
// rounding of the lifts and of these products.
constexpr double kInSphereLiftFactor = 1.05 * (16.0 + 224.0 * kEpsilon) * kEpsilon;
constexpr double kInSphereLift = 108 * kInSphereLiftFactor * kInSphereLiftFactor;
// Below this magnitude products may have underflowed and the relative bounds no longer hold.
constexpr double kUnderflowGuard = 1e-250;

// For coordinates of any magnitude (Predicates::allowAnyMagnitude()) the semi-static filters also
// require every largest difference within [2^-k, 2^k]. Then no operation overflows (orient3d's
// products stay below 2^600, insphere's below 2^607), and a rounding error lost to underflow (at
// most 2^-1075, times the factors it is multiplied by afterwards, below 2^362) stays below 2^-60
// of the bound, which the bounds' 2% margin covers.
/// Error bounds of the float orient3d and insphere determinants of records whose differences
/// are at most e[k] along axis k, where the exact points' differences lie within eps of the
/// records' (periodic images' rounded records; 0 for exact points): the semi-static bounds at
/// e + eps, plus the exact determinants' growth from e to e + eps, P(e + eps) - P(e), P the
/// determinant with every term made positive (a polynomial in the differences with positive
/// coefficients, so its growth bounds any change of them by at most eps): 6 ex ey ez for
/// orient3d, 24 (ex^2 + ey^2 + ez^2) ex ey ez for insphere (4 lifts, each with a 6-term minor).
/// 1% for the rounding of all that. Valid where the products neither under- nor overflow.
struct RecordBounds
{
  double orient, inSphere;
};
/// The terms those bounds are made of: the extents' product at e + eps and their largest, the
/// sum of their squares at e, and the growths from e to e + eps, P(e + eps) - P(e), of the product
/// and of the sum of squares, summed from positive terms (no cancellation).
struct RecordGrowth
{
  double product, largest, squares, productGrowth, squaresGrowth;
  RecordGrowth(const double e[3], double eps)
  {
    const double ex = e[0] + eps, ey = e[1] + eps, ez = e[2] + eps;
    largest = std::max({ex, ey, ez});
    product = ex * ey * ez;
    squares = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    productGrowth = eps * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]) +
      eps * eps * (e[0] + e[1] + e[2]) + eps * eps * eps;
    squaresGrowth = 2 * eps * (e[0] + e[1] + e[2]) + 3 * eps * eps;
  }
};
inline RecordBounds recordBounds(const double e[3], double eps)
{
  const RecordGrowth g(e, eps);
  const double orientGrowth = 6 * g.productGrowth;
  const double inSphereGrowth = 24 * (g.squaresGrowth * g.product + g.squares * g.productGrowth);
  return {(kOrientSemiStatic * g.product + orientGrowth) * 1.01,
    (kInSphereSemiStatic * (g.largest * g.largest * g.product) + inSphereGrowth) * 1.01};
}

/// The power test's error bound (Predicates::powerTest()) for records whose differences are at
/// most e[k] along axis k and within eps of the exact points' (recordBounds()), of weights whose
/// differences are at most `spread`: the semi-static bound at e + eps, plus the exact
/// determinant's growth from e to e + eps, its positive form being 24 (ex^2 + ey^2 + ez^2 +
/// spread) ex ey ez (4 lowered lifts, each with a 6-term minor). 1% for the rounding of all that.
inline double powerRecordBound(const double e[3], double spread, double eps)
{
  const RecordGrowth g(e, eps);
  const double growth = 24 * (g.squaresGrowth * g.product + (g.squares + spread) * g.productGrowth);
  return (kPowerSemiStatic * g.product * (3 * g.largest * g.largest + spread) + growth) * 1.01;
}

constexpr double kOrientRange = 0x1p200;
constexpr double kInSphereRange = 0x1p120;

inline bool withinRange(double range, double x, double y, double z)
{
  return std::min({x, y, z}) >= 1 / range && std::max({x, y, z}) <= range;
}

template <typename T>
int signOf(T x) // for doubles here, and 128-bit integers in the exact stage
{
  return (x > 0) - (x < 0);
}
} // namespace filter

class Predicates
{
public:
  /// `perturbationSeed` picks the perturbation's order (perturbationKey()).
  explicit Predicates(std::uint64_t perturbationSeed = 1) : perturbationSeed_(perturbationSeed) {}

  int orient3d(const double* a, const double* b, const double* c, const double* d);
  int inSphere(const double* a, const double* b, const double* c, const double* d, const double* e);
  /// inSphere's float stage alone: its sign when the float filters prove it, else 0 (undecided).
  int inSphereFiltered(
    const double* a, const double* b, const double* c, const double* d, const double* e);
  /// inSphereFiltered() for the determinant `det` and the lifts already computed from the same
  /// points (inSphereDeterminant()). The static filter goes first until preferLiftsFilter().
  int inSphereFiltered(double det, const double lifts[4], const double* a, const double* b,
    const double* c, const double* d, const double* e);
  /// Exactly: is c on the line through a and b (or a == b)?
  bool collinear(const double* a, const double* b, const double* c);

  /// inSphere with ties broken by symbolic perturbation: the lifted coordinate |p|^2 of every point
  /// is lowered by an infinitesimal that is larger for a point earlier in the perturbation's order
  /// (precedes()). Never returns 0 for a non-degenerate tetrahedron. p[i] are the points of a
  /// positively oriented tetrahedron, pe the query. The first point dominates, which on
  /// cospherical input pulls every tetrahedron towards it: a fan of about 2 tetrahedra per point
  /// instead of a dense tangle.
  int inSphereSoS(const double* const p[4], const double* pe);
  /// The power test, inSphere() for weighted points (power distance |x - p|^2 - w): > 0 iff pe,
  /// of weight we, has a negative power distance to the orthogonal sphere of the positive
  /// tetrahedron p[0..3] of weights w[0..3], i.e. conflicts with it in the regular
  /// tetrahedralization; 0 on a tie. The determinant is insphere's with each lifted coordinate
  /// |p|^2 lowered by p's weight: a float evaluation under a semi-static bound, else exact over
  /// integers of unbounded size (weights of any finite magnitude).
  int powerTest(const double* const p[4], const double* pe, const double w[4], double we);
  /// powerTest() with ties broken by inSphereSoS()'s perturbation. It lowers the lifted
  /// coordinates, which the weights only shift, so its terms, and the order it breaks ties in, are
  /// the unweighted ones.
  int powerTestSoS(const double* const p[4], const double* pe, const double w[4], double we)
  {
    const int s = powerTest(p, pe, w, we);
    return s != 0 ? s : symbolicInSphere(p, pe);
  }
  /// inSphereSoS(p, pe) > 0, all the cavity search asks: where the static filter decides, which
  /// it does for nearly every test, one comparison after the determinant (InSphereProbe).
  bool insideSoS(const double* const p[4], const double* pe);
  /// insideSoS() for a test that the first filter (the static one, or the lifts' one where
  /// preferred) left open: the rest of the filters, then the exact stage and the perturbation.
  bool insideBeyondFirstFilter(
    const double* a, const double* b, const double* c, const double* d, const double* e);
  /// The static bound of insphere: a float determinant beyond it has the exact sign.
  double inSphereStaticBound() const { return tuning_.inSphereStatic; }
  /// The power test's static bound (PowerProbe), for weights within [lowest, highest], in the
  /// points' box of adaptTo(): filter::kPowerSemiStatic at the box's extents and the weights'
  /// spread (with images, filter::powerRecordBound(), the records' slack added). Infinite (no
  /// static decision) for any magnitude or a spread beyond the normal range.
  void adaptToWeights(double lowest, double highest);
  double powerStaticBound() const { return tuning_.powerStatic; }
  /// The lifts' filter (filter::kInSphereLift) on a determinant and its lifts.
  bool liftsFilterProves(double det, const double lifts[4]) const;

  /// Tunes the predicates to a point set within `box` (point i at xyz + i * stride); every point
  /// passed from then on must lie in the box and be one of them or of those include()d later.
  /// From the box's extent come static error bounds, checked before the semi-static ones (one
  /// comparison decides almost every call on well-spread points). When every coordinate is an
  /// integer multiple of one power of two u, below 2^kIntegerGridBits u in magnitude (lattices,
  /// image and integer data), the exact stage runs in 128-bit integers instead of expansions (where
  /// the compiler has them), and below 2^kFloatExactOrientBits u (orient3d) or
  /// 2^kFloatExactInSphereBits u (insphere) the float evaluation itself is exact, so even a tie
  /// costs no more than the float evaluation.
  void adaptTo(const double* xyz, std::size_t count, std::size_t stride, const Bounds& box);
  /// Widens the tuning to more points of the same box (the grid may get finer, or go).
  void include(const double* xyz, std::size_t count, std::size_t stride);
  /// Widens the static bounds to `box`, which holds adaptTo()'s and every point passed from now
  /// on (points added beyond the first ones' box: the Voronoi cells' far points, a rank's
  /// ghosts); the grid stays include()'s. The power test's bound then needs adaptToWeights()
  /// again.
  void widenTo(const Bounds& box);
  /// Takes other's tuning, keeping this one's counters.
  void tuneLike(const Predicates& other)
  {
    tuning_ = other.tuning_;
    liftsFirst_ = liftsFirst_ && !tuning_.anyMagnitude && !tuning_.images;
  }
  /// For the vertices of a periodic run, whose records hold images rounded (PeriodicImages.h):
  /// every sign is then the exact images', and ties are broken in the images' order. The static
  /// filters widen by the rounding of the records (applyBoxBounds()); every test they leave open on
  /// an image that its record does not hold is decided exactly, with the residuals, in GMP
  /// integers, the power test's too. No grid or lifts' filter then.
  void useImages(const PeriodicImages* images);
  /// For coordinates of any finite magnitude, from the smallest subnormal to DBL_MAX (points that
  /// no scaled frame holds exactly): the float filters check that no operation overflowed or lost
  /// a rounding error to underflow, and the exact stage computes in GMP integers on the
  /// coordinates' binary values, which neither overflow nor underflow. Ends the grid's shortcuts.
  void allowAnyMagnitude();
  /// From now on the lifts' filter goes first. The static filter, one comparison, decides nearly
  /// every insphere test on volume points, but on surface samples, whose local scale is far below
  /// the box's, it leaves many of them open, and a branch on it is then a coin toss to the
  /// predictor. The lifts' filter decides nearly all of those, at the price of a few products per
  /// test. It cannot help with exact ties (cospherical points, lattices), which
  /// neither filter decides. Which filter goes first never changes a sign.
  /// Not for any magnitude: its bound assumes that no rounding error is lost to underflow.
  void preferLiftsFilter() { liftsFirst_ = !tuning_.anyMagnitude && !tuning_.images; }
  bool prefersLiftsFilter() const { return liftsFirst_; }
  /// Insphere tests that the static filter left open and the lifts' filter decided, while the
  /// static one went first.
  std::size_t liftsFilterRescues() const { return liftsFilterRescues_; }
  static constexpr int kIntegerGridBits = 23;
  static constexpr int kFloatExactOrientBits = 15;
  static constexpr int kFloatExactInSphereBits = 8;

  std::size_t exactOrientCalls = 0;
  std::size_t doubleDoubleInSphereCalls = 0; ///< insphere calls past the float filters
  std::size_t exactInSphereCalls = 0;        ///< of those, the ones double-double left open
  std::size_t symbolicTies = 0;
  /// Exact evaluations in GMP integers (allowAnyMagnitude()).
  std::size_t integerExactCalls = 0;

private:
  template <int N>
  void gridDifferences(const double* const x[N], const double* y, std::int64_t out[N][3]) const;
  /// orient3d() for a determinant `det` that the static filter left open: the semi-static filter,
  /// then the exact stage.
  int orient3dBeyondStatic(
    double det, const double* a, const double* b, const double* c, const double* d);
  int orient3dExact(const double* a, const double* b, const double* c, const double* d);
  int inSphereDoubleDouble(
    const double* a, const double* b, const double* c, const double* d, const double* e);
  /// The insphere sign from the coordinate differences x (row r: point r less the fifth point)
  /// in double-double, where it clears `coefficient` times the permanent over the magnitudes m;
  /// else kUndecided.
  int inSphereOfDifferences(
    const DoubleDouble x[4][3], const double m[4][3], double coefficient) const;
  /// inSphereOfDifferences() over periodic images' exact differences (records and residuals).
  int inSphereOfImagesDoubleDouble(
    const double* a, const double* b, const double* c, const double* d, const double* e);
  int symbolicInSphere(const double* const p[4], const double* pe);
  int inSphereExact(
    const double* a, const double* b, const double* c, const double* d, const double* e);
  /// The power test over integers; periodic images' records (useImages()) with their residuals.
  int powerTestExact(const double* const p[4], const double* pe, const double w[4], double we);
  /// The exact stages of periodic images (useImages()).
  int orient3dOfImages(const double* a, const double* b, const double* c, const double* d);
  int inSphereOfImages(
    const double* a, const double* b, const double* c, const double* d, const double* e);
  bool collinearOfImages(const double* a, const double* b, const double* c);
  /// p's residual where p is an image's record, else null.
  const double* residualOf(const double* p) const
  {
    const ImageOf* image = tuning_.images->find(p);
    return image ? image->residual : nullptr;
  }
  /// p's residual, zeros where p is no image's record.
  const double* residualOrNone(const double* p) const;
  /// Whether any of the points is an image that its record does not hold exactly: the others,
  /// exact doubles, take the usual filters and exact stages.
  template <typename... Points>
  bool anyInexact(const Points*... p) const
  {
    auto inexact = [this](const double* q) {
      const double* r = residualOf(q);
      return r && (r[0] != 0 || r[1] != 0 || r[2] != 0);
    };
    return (inexact(p) || ...);
  }
  static constexpr int kUndecided = 2;
  /// inSphereExact() of the tetrahedron five[0..3] and five[4] where four of the five share one
  /// coordinate exactly (a face of a structured grid, a layer, a ring): its sign from the fifth
  /// point's side of their plane and an exact incircle test in it. kUndecided when no four do.
  int inSphereOnAxisPlane(const double* const five[5]);
  /// The sign of the homogeneous incircle determinant of p[0..3] in the axes u < v: in floats,
  /// then double-double, then exactly (inCircleExact()).
  int inCircle(const double* const p[4], int u, int v);
  int inCircleExact(const double* const p[4], int u, int v);
  Expansion minor3(Expansion const u[3], Expansion const v[3], Expansion const w[3]);

  /// Whether a semi-static bound on a product of differences as large as `scale` holds: no
  /// product underflowed and, for any magnitude, the largest differences are within `range`.
  bool semiStaticHolds(double scale, double range, const double largest[3]) const
  {
    return scale > filter::kUnderflowGuard &&
      (!tuning_.anyMagnitude || filter::withinRange(range, largest[0], largest[1], largest[2]));
  }

  ExpansionArena arena_;
  std::uint64_t perturbationSeed_;
  bool liftsFirst_ = false;
  std::size_t liftsFilterRescues_ = 0;
  struct Tuning
  {
    // The points' grid: every |x| < 2^highest, every x a multiple of 2^lowest (kNoGrid when none).
    static constexpr int kNoGrid = -4096;
    int lowest = 4096, highest = kNoGrid;
    double boxOrient = HUGE_VAL, boxInSphere = HUGE_VAL; // static bounds from the box alone
    double inverseGridUnit = 0.0;                        // 1/u on an integer grid, else 0
    // A float determinant beyond these bounds has the exact sign; +inf until adaptTo(), 0 where the
    // float evaluation is exact. floatExact* tells that a determinant within them is exactly 0.
    double orientStatic = HUGE_VAL;
    double inSphereStatic = HUGE_VAL;
    double powerStatic = HUGE_VAL;                      // adaptToWeights()
    double extents[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}; // the box's, from adaptTo()
    double magnitude = HUGE_VAL;                        // the largest |coordinate| in the box
    double imageSlack = 0; // how far images' differences may lie from their records' (useImages())
    bool floatExactOrient = false;
    bool floatExactInSphere = false;
    bool anyMagnitude = false;              // allowAnyMagnitude()
    const PeriodicImages* images = nullptr; // useImages()
  } tuning_;
  void applyGrid();
  /// The static bounds from `box` alone (boxOrient, boxInSphere, extents, magnitude).
  void setBoxBounds(const Bounds& box);
  /// boxOrient and boxInSphere from the box's extents and magnitude.
  void applyBoxBounds();
};

// Only the static filter is inline: it decides nearly every call, and where the rest was inlined
// too the compiler left the whole test out of line, a call for each of them.
inline int Predicates::orient3d(const double* a, const double* b, const double* c, const double* d)
{
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  // det[a-d; b-d; c-d] is the negative of VTK's orientation.
  const double det =
    adz * (bdx * cdy - cdx * bdy) + bdz * (cdx * ady - adx * cdy) + cdz * (adx * bdy - bdx * ady);
  // One comparison of |det|: det > bound || -det > bound compiled to a first branch on det's sign.
  if (std::fabs(det) > tuning_.orientStatic)
    return -filter::signOf(det);
  return orient3dBeyondStatic(det, a, b, c, d);
}

/// det[(x-e, |x-e|^2) for x = a,b,c,d]: positive means inside for the negative orientation, i.e.
/// outside for VTK's positive one. In the order of operations that the error bounds of
/// inSphereFiltered() assume. `lifts`, when given, receives the four |x-e|^2 as computed.
/// `lowered`, when given, lowers them by its four values first (the power test's weight
/// differences w_x - w_e), which filter::kPowerSemiStatic bounds.
inline double inSphereDeterminantPlain(const double* a, const double* b, const double* c,
  const double* d, const double* e, double* lifts = nullptr, const double* lowered = nullptr)
{
  const double aex = a[0] - e[0], aey = a[1] - e[1], aez = a[2] - e[2];
  const double bex = b[0] - e[0], bey = b[1] - e[1], bez = b[2] - e[2];
  const double cex = c[0] - e[0], cey = c[1] - e[1], cez = c[2] - e[2];
  const double dex = d[0] - e[0], dey = d[1] - e[1], dez = d[2] - e[2];
  const double ab = aex * bey - bex * aey, bc = bex * cey - cex * bey, cd = cex * dey - dex * cey;
  const double da = dex * aey - aex * dey, ac = aex * cey - cex * aey, bd = bex * dey - dex * bey;
  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;
  double alift = aex * aex + aey * aey + aez * aez;
  double blift = bex * bex + bey * bey + bez * bez;
  double clift = cex * cex + cey * cey + cez * cez;
  double dlift = dex * dex + dey * dey + dez * dez;
  if (lowered)
  {
    alift -= lowered[0];
    blift -= lowered[1];
    clift -= lowered[2];
    dlift -= lowered[3];
  }
  if (lifts)
  {
    lifts[0] = alift;
    lifts[1] = blift;
    lifts[2] = clift;
    lifts[3] = dlift;
  }
  return (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
}

/// The point e of insphere tests, loaded as inSphereDeterminant() uses it: many tests against
/// one e (a cavity's) load it once.
struct InSphereApex
{
  explicit InSphereApex(const double* e)
#if defined(__AVX__)
    : x(_mm256_set1_pd(e[0])), y(_mm256_set1_pd(e[1])), z(_mm256_set1_pd(e[2]))
#elif defined(__SSE2__)
    : xy(_mm_loadu_pd(e)), z(_mm_set1_pd(e[2]))
#else
    : point(e)
#endif
  {}
#if defined(__AVX__)
  __m256d x, y, z;
#elif defined(__SSE2__)
  __m128d xy, z;
#else
  const double* point;
#endif
};

#if defined(__AVX__)
namespace lanes
{
/// (v1, v2, v3, v0)
inline __m256d rotate(__m256d v)
{
  return _mm256_shuffle_pd(v, _mm256_permute2f128_pd(v, v, 1), 0b0101);
}
/// (v3, v0, v1, v2)
inline __m256d rotateBack(__m256d v)
{
  return _mm256_shuffle_pd(_mm256_permute2f128_pd(v, v, 1), v, 0b0101);
}
/// (v2, v3, v0, v1)
inline __m256d swapHalves(__m256d v)
{
  return _mm256_permute2f128_pd(v, v, 1);
}
/// Four points less e, one point to a lane: x = (ax - ex, bx - ex, cx - ex, dx - ex), and so on.
struct FromApex
{
  FromApex(
    const InSphereApex& e, const double* a, const double* b, const double* c, const double* d)
  {
    // (ax, ay, cx, cy) and (bx, by, dx, dy) give the x and y lanes.
    const __m256d ac =
      _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(a)), _mm_loadu_pd(c), 1);
    const __m256d bd =
      _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(b)), _mm_loadu_pd(d), 1);
    x = _mm256_sub_pd(_mm256_unpacklo_pd(ac, bd), e.x);
    y = _mm256_sub_pd(_mm256_unpackhi_pd(ac, bd), e.y);
    z = _mm256_sub_pd(_mm256_set_pd(d[2], c[2], b[2], a[2]), e.z);
  }
  /// (|a - e|^2, |b - e|^2, |c - e|^2, |d - e|^2), as distance2() computes each.
  __m256d distances2() const
  {
    return _mm256_add_pd(
      _mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)), _mm256_mul_pd(z, z));
  }
  __m256d x, y, z;
};
} // namespace lanes
#endif

/// inSphereDeterminantPlain(a, b, c, d, e), in lanes: with AVX, the four points' coordinates are
/// four lanes, and a-b-c-d cyclic shifts of them make the minors; with SSE2 (every x86-64), two
/// lanes at once. Each lane does the very operations of the plain form, with a - (-b) for a + b
/// where a minor comes out negated (both exact the same), so every form gives the same double
/// (TestPredicates checks it).
inline double inSphereDeterminant(const InSphereApex& e, const double* a, const double* b,
  const double* c, const double* d, double* lifts = nullptr, const double* lowered = nullptr)
{
#if defined(__AVX__)
  using namespace lanes;
  const FromApex points(e, a, b, c, d);
  const __m256d x = points.x, y = points.y, z = points.z;
  // (ab, bc, cd, da) and (ac, bd, -ac, -bd).
  const __m256d m = _mm256_sub_pd(_mm256_mul_pd(x, rotate(y)), _mm256_mul_pd(rotate(x), y));
  const __m256d n = _mm256_sub_pd(_mm256_mul_pd(x, swapHalves(y)), _mm256_mul_pd(swapHalves(x), y));
  // (abc, bcd, cda, dab)
  const __m256d t =
    _mm256_add_pd(_mm256_sub_pd(_mm256_mul_pd(z, rotate(m)), _mm256_mul_pd(rotate(z), n)),
      _mm256_mul_pd(swapHalves(z), m));
  // (alift, blift, clift, dlift)
  __m256d l = points.distances2();
  if (lowered)
    l = _mm256_sub_pd(l, _mm256_loadu_pd(lowered));
  if (lifts)
    _mm256_storeu_pd(lifts, l);
  // (dlift * abc, alift * bcd, blift * cda, clift * dab), then
  // (dlift * abc - clift * dab) + (blift * cda - alift * bcd).
  const __m256d w = _mm256_mul_pd(rotateBack(l), t);
  const __m128d low = _mm256_castpd256_pd128(w), high = _mm256_extractf128_pd(w, 1);
  const __m128d halves = _mm_sub_pd(_mm_unpacklo_pd(low, high), _mm_shuffle_pd(high, low, 3));
  return _mm_cvtsd_f64(_mm_add_sd(halves, _mm_unpackhi_pd(halves, halves)));
#elif defined(__SSE2__)
  const __m128d exy = e.xy, ez = e.z;
  const __m128d axy = _mm_sub_pd(_mm_loadu_pd(a), exy), bxy = _mm_sub_pd(_mm_loadu_pd(b), exy);
  const __m128d cxy = _mm_sub_pd(_mm_loadu_pd(c), exy), dxy = _mm_sub_pd(_mm_loadu_pd(d), exy);
  const __m128d zab = _mm_sub_pd(_mm_set_pd(b[2], a[2]), ez); // (aez, bez)
  const __m128d zcd = _mm_sub_pd(_mm_set_pd(d[2], c[2]), ez); // (cez, dez)
  const __m128d zbc = _mm_shuffle_pd(zab, zcd, 1), zda = _mm_shuffle_pd(zcd, zab, 1);
  const __m128d xac = _mm_unpacklo_pd(axy, cxy), yac = _mm_unpackhi_pd(axy, cxy);
  const __m128d xbd = _mm_unpacklo_pd(bxy, dxy), ybd = _mm_unpackhi_pd(bxy, dxy);
  const __m128d xab = _mm_unpacklo_pd(axy, bxy), yab = _mm_unpackhi_pd(axy, bxy);
  const __m128d xcd = _mm_unpacklo_pd(cxy, dxy), ycd = _mm_unpackhi_pd(cxy, dxy);
  const __m128d xca = _mm_shuffle_pd(xac, xac, 1), yca = _mm_shuffle_pd(yac, yac, 1);
  // The 2x2 minors in pairs: (ab, cd), (bc, da), (ac, bd).
  const __m128d abcd = _mm_sub_pd(_mm_mul_pd(xac, ybd), _mm_mul_pd(xbd, yac));
  const __m128d bcda = _mm_sub_pd(_mm_mul_pd(xbd, yca), _mm_mul_pd(xca, ybd));
  const __m128d acbd = _mm_sub_pd(_mm_mul_pd(xab, ycd), _mm_mul_pd(xcd, yab));
  // (abc, bcd) and (cda, dab).
  const __m128d t1 =
    _mm_add_pd(_mm_sub_pd(_mm_mul_pd(zab, _mm_move_sd(abcd, bcda)), _mm_mul_pd(zbc, acbd)),
      _mm_mul_pd(zcd, _mm_unpacklo_pd(abcd, bcda)));
  const __m128d t2 =
    _mm_add_pd(_mm_add_pd(_mm_mul_pd(zcd, _mm_shuffle_pd(bcda, abcd, 1)), _mm_mul_pd(zda, acbd)),
      _mm_mul_pd(zab, _mm_unpackhi_pd(abcd, bcda)));
  // (alift, blift) and (clift, dlift).
  __m128d lab =
    _mm_add_pd(_mm_add_pd(_mm_mul_pd(xab, xab), _mm_mul_pd(yab, yab)), _mm_mul_pd(zab, zab));
  __m128d lcd =
    _mm_add_pd(_mm_add_pd(_mm_mul_pd(xcd, xcd), _mm_mul_pd(ycd, ycd)), _mm_mul_pd(zcd, zcd));
  if (lowered)
  {
    lab = _mm_sub_pd(lab, _mm_loadu_pd(lowered));
    lcd = _mm_sub_pd(lcd, _mm_loadu_pd(lowered + 2));
  }
  if (lifts)
  {
    _mm_storeu_pd(lifts, lab);
    _mm_storeu_pd(lifts + 2, lcd);
  }
  // (dlift * abc - clift * dab, blift * cda - alift * bcd), then the sum of the two.
  const __m128d halves = _mm_sub_pd(_mm_mul_pd(_mm_unpackhi_pd(lcd, lab), _mm_unpacklo_pd(t1, t2)),
    _mm_mul_pd(_mm_unpacklo_pd(lcd, lab), _mm_shuffle_pd(t2, t1, 3)));
  return _mm_cvtsd_f64(_mm_add_sd(halves, _mm_unpackhi_pd(halves, halves)));
#else
  return inSphereDeterminantPlain(a, b, c, d, e.point, lifts, lowered);
#endif
}

inline double inSphereDeterminant(const double* a, const double* b, const double* c,
  const double* d, const double* e, double* lifts = nullptr)
{
  return inSphereDeterminant(InSphereApex(e), a, b, c, d, lifts);
}

inline int Predicates::inSphereFiltered(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  double lifts[4];
  const double det = inSphereDeterminant(a, b, c, d, e, lifts);
  return inSphereFiltered(det, lifts, a, b, c, d, e);
}

// The lifts' filter (filter::kInSphereLift): a few products of values at hand.
inline bool Predicates::liftsFilterProves(double det, const double lifts[4]) const
{
  const double liftProduct = (lifts[0] * lifts[1]) * (lifts[2] * lifts[3]);
  const double liftBound =
    filter::kInSphereLift * liftProduct * ((lifts[0] + lifts[1]) + (lifts[2] + lifts[3]));
  // A bound in the normal range keeps every product above it normal too (relative rounding).
  return det * det > liftBound && liftBound > filter::kUnderflowGuard;
}

inline int Predicates::inSphereFiltered(double det, const double lifts[4], const double* a,
  const double* b, const double* c, const double* d, const double* e)
{
  if (liftsFirst_ && liftsFilterProves(det, lifts))
    return -filter::signOf(det);
  if (det > tuning_.inSphereStatic || -det > tuning_.inSphereStatic)
    return -filter::signOf(det);
  const bool inexact = tuning_.images && anyInexact(a, b, c, d, e);
  if (tuning_.floatExactInSphere && !inexact)
    return -filter::signOf(det);
  if (!liftsFirst_ && !tuning_.anyMagnitude && !inexact && liftsFilterProves(det, lifts))
  {
    ++liftsFilterRescues_;
    return -filter::signOf(det);
  }

  // Semi-static filter: each lift is at most 3 m^2 (m the largest difference) and each 3x3
  // permanent at most 6 mx my mz, so the permanent is at most 72 m^2 mx my mz and Shewchuk's bound
  // (16 + 224 eps) eps * permanent is below filter::kInSphereSemiStatic * m^2 * mx * my * mz.
  double largest[3];
  for (int k = 0; k < 3; ++k)
    largest[k] = std::max({std::fabs(a[k] - e[k]), std::fabs(b[k] - e[k]), std::fabs(c[k] - e[k]),
      std::fabs(d[k] - e[k])});
  const double m = std::max({largest[0], largest[1], largest[2]});
  const double scale = m * m * largest[0] * largest[1] * largest[2];
  // For images with rounded records, widened as orient3d()'s.
  const double bound = inexact ? filter::recordBounds(largest, tuning_.imageSlack).inSphere
                               : filter::kInSphereSemiStatic * scale;
  if ((det > bound || -det > bound) && semiStaticHolds(scale, filter::kInSphereRange, largest))
    return -filter::signOf(det);
  return 0;
}

inline int Predicates::inSphere(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  const int filtered = inSphereFiltered(a, b, c, d, e);
  if (filtered != 0 || tuning_.floatExactInSphere)
    return filtered;
  return inSphereDoubleDouble(a, b, c, d, e);
}

inline int Predicates::inSphereSoS(const double* const p[4], const double* pe)
{
  const int s = inSphere(p[0], p[1], p[2], p[3], pe);
  return s != 0 ? s : symbolicInSphere(p, pe);
}

/// The cavity search's tests of one insertion: is each tetrahedron's circumsphere around the new
/// point e (Predicates::insideSoS())? e and the filter's choice are loaded once for them all, and
/// a test that the first filter leaves open goes out of line.
class InSphereProbe
{
public:
  InSphereProbe(Predicates& predicates, const double* e)
    : predicates_(predicates), e_(e), apex_(e), staticBound_(predicates.inSphereStaticBound()),
      liftsFirst_(predicates.prefersLiftsFilter())
  {}
  /// Whether e lies in the circumsphere of the positive tetrahedron abcd, ties broken
  /// symbolically.
  bool inside(const double* a, const double* b, const double* c, const double* d) const
  {
    const auto open = [&] { return predicates_.insideBeyondFirstFilter(a, b, c, d, e_); };
    return liftsFirst_ ? insideFirstFiltered<true>(a, b, c, d, open)
                       : insideFirstFiltered<false>(a, b, c, d, open);
  }
  /// inside(), which calls `open` for a test the first filter leaves open: a caller that can find
  /// the points again keeps no pointer to them alive across the test. The caller names the first
  /// filter, the lifts' filter when Predicates::prefersLiftsFilter(), so that a loop of tests
  /// does not ask which on every one.
  template <bool LiftsFirst, class Open>
  bool insideFirstFiltered(
    const double* a, const double* b, const double* c, const double* d, Open open) const
  {
    assert(LiftsFirst == liftsFirst_);
    double lifts[4];
    const double det = inSphereDeterminant(apex_, a, b, c, d, lifts);
    if (LiftsFirst ? predicates_.liftsFilterProves(det, lifts) : std::fabs(det) > staticBound_)
      return det < 0;
    return open();
  }
  /// Whether the first filter alone proves e inside the circumsphere: false may be a tie or a
  /// test the filter left open.
  bool provenInside(const double* a, const double* b, const double* c, const double* d) const
  {
    double lifts[4];
    const double det = inSphereDeterminant(apex_, a, b, c, d, lifts);
    const bool decided =
      liftsFirst_ ? predicates_.liftsFilterProves(det, lifts) : std::fabs(det) > staticBound_;
    return decided && det < 0;
  }

private:
  Predicates& predicates_;
  const double* e_;
  InSphereApex apex_;
  double staticBound_;
  bool liftsFirst_;
};

/// The cavity search's power tests of one weighted insertion (InSphereProbe's weighted form): does
/// the new point e, of weight we, conflict with each tetrahedron (Predicates::powerTestSoS())?
/// The static filter decides nearly every test in the lanes of inSphereDeterminant().
class PowerProbe
{
public:
  PowerProbe(Predicates& predicates, const double* e, double we)
    : predicates_(predicates), e_(e), we_(we), apex_(e), staticBound_(predicates.powerStaticBound())
  {}
  /// Whether e conflicts with the positive tetrahedron abcd of weights wa, wb, wc, wd, ties
  /// broken symbolically. The cavity search has each of them at hand: no array of points or
  /// weights is built for a test that the static filter decides.
  bool inside(const double* a, const double* b, const double* c, const double* d, double wa,
    double wb, double wc, double wd) const
  {
    const double lowered[4] = {wa - we_, wb - we_, wc - we_, wd - we_};
    const double det = inSphereDeterminant(apex_, a, b, c, d, nullptr, lowered);
    // One comparison of |det|: "det > bound || -det > bound" compiled to a first branch on det's
    // sign, the test's outcome, which the predictor misses half the time.
    if (std::fabs(det) > staticBound_)
      return det < 0;
    const double* const p[4] = {a, b, c, d};
    const double w[4] = {wa, wb, wc, wd};
    return predicates_.powerTestSoS(p, e_, w, we_) > 0;
  }
  bool inside(const double* const p[4], const double w[4]) const
  {
    return inside(p[0], p[1], p[2], p[3], w[0], w[1], w[2], w[3]);
  }
  /// Whether the static filter alone proves that e conflicts with p: false may be a tie or a test
  /// the filter left open.
  bool provenInside(const double* const p[4], const double w[4]) const
  {
    const double lowered[4] = {w[0] - we_, w[1] - we_, w[2] - we_, w[3] - we_};
    return -inSphereDeterminant(apex_, p[0], p[1], p[2], p[3], nullptr, lowered) > staticBound_;
  }

private:
  Predicates& predicates_;
  const double* e_;
  double we_;
  InSphereApex apex_;
  double staticBound_;
};

inline bool Predicates::insideSoS(const double* const p[4], const double* pe)
{
  return InSphereProbe(*this, pe).inside(p[0], p[1], p[2], p[3]);
}

} // namespace fd3

#endif
