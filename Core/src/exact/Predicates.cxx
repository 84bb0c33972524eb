#include "exact/Predicates.h"

#include "exact/DoubleDouble.h"
#include "system/Platform.h"

#include <gmp.h>

#include <algorithm>
#include <cassert>
#include <climits>
#include <cmath>
#include <cstring>

namespace fd3
{
namespace
{
using filter::signOf;

#ifdef FD3_HAVE_INT128
using Int128 = __int128;

Int128 det3(const std::int64_t u[3], const std::int64_t v[3], const std::int64_t w[3])
{
  const Int128 cx = Int128(v[1]) * w[2] - Int128(v[2]) * w[1];
  const Int128 cy = Int128(v[2]) * w[0] - Int128(v[0]) * w[2];
  const Int128 cz = Int128(v[0]) * w[1] - Int128(v[1]) * w[0];
  return u[0] * cx + u[1] * cy + u[2] * cz;
}
#endif

// Bound on the error of the double-double insphere determinant, relative to its permanent
// (DoubleDouble.h): along the expression, products add 8 u^2 and sums 3 u^2 to the relative error
// of their operands, which gives 11 u^2 for the 2x2 minors, 25 u^2 for the 3x3 minors, 14 u^2 for
// the lifts and 53 u^2 for the determinant. Doubled, for the rounding of the permanent itself and
// higher-order terms.
constexpr double kUnitRoundoff = filter::kEpsilon;
constexpr double kInSphereDoubleDouble = 2 * 53 * kUnitRoundoff * kUnitRoundoff;
// The same for the 2D incircle determinant: 11 u^2 for the 2x2 minors and the lifts, 36 u^2 for
// the determinant; doubled.
constexpr double kInCircleDoubleDouble = 2 * 36 * kUnitRoundoff * kUnitRoundoff;
// The same over the differences of periodic images (record plus residual each, PeriodicImages.h):
// each difference is the double-double sum of the records' and the residuals' exact differences,
// within 3 u^2 of the magnitudes summed, which the permanent is taken over; through the
// determinant's degree 5 that adds 15 u^2. Doubled as above.
constexpr double kInSphereImagesDoubleDouble = 2 * (53 + 15) * kUnitRoundoff * kUnitRoundoff;
// Below this permanent the low parts could reach the subnormal range: left to the exact stage.
constexpr double kDoubleDoubleSmallest = 0x1p-600;
// The residual of a point that is no rounded image: none.
constexpr double kNoResidual[3] = {0, 0, 0};

/// GMP integers that free themselves.
class Integer
{
public:
  Integer() { mpz_init(value_); }
  ~Integer() { mpz_clear(value_); }
  Integer(const Integer&) = delete;
  Integer& operator=(const Integer&) = delete;
  mpz_ptr get() { return value_; }
  mpz_srcptr get() const { return value_; }

private:
  mpz_t value_;
};

// An exact evaluation over integers: each finite double is m 2^k with an integer |m| < 2^53, so
// the coordinates of one call, brought to their smallest k, are integers (of at most 2^2151): the
// determinants are then polynomials in integers, which GMP computes without rounding, whatever
// the magnitudes. The common factor 2^k is positive and leaves every sign alone.
template <int N>
class IntegerRows
{
public:
  /// Rows x[i] - y, for N points x and the point y, counting a power of two no higher than
  /// 2^`highestScale`.
  IntegerRows(const double* const x[N], const double* y, int highestScale = INT_MAX)
    : IntegerRows(x, y, nullptr, nullptr, highestScale)
  {}
  /// The same for points whose exact coordinates are x[i] + xr[i] and y + yr, each residual a
  /// point or null for none (PeriodicImages.h).
  IntegerRows(const double* const x[N], const double* y, const double* const xr[N],
    const double* yr, int highestScale = INT_MAX)
  {
    const double* const none = kNoResidual;
    int lowest = highestScale;
    auto lower = [&lowest](double v) {
      if (v != 0)
        lowest = std::min(lowest, unitExponent(v));
    };
    for (int k = 0; k < 3; ++k)
    {
      lower(y[k]);
      lower((yr ? yr : none)[k]);
      for (int i = 0; i < N; ++i)
      {
        lower(x[i][k]);
        lower((xr && xr[i] ? xr[i] : none)[k]);
      }
    }
    lowest_ = lowest == INT_MAX ? 0 : lowest;
    Integer origin, part;
    for (int k = 0; k < 3; ++k)
    {
      set(origin, y[k], lowest);
      set(part, (yr ? yr : none)[k], lowest);
      mpz_add(origin.get(), origin.get(), part.get());
      for (int i = 0; i < N; ++i)
      {
        set(row_[i][k], x[i][k], lowest);
        set(part, (xr && xr[i] ? xr[i] : none)[k], lowest);
        mpz_add(row_[i][k].get(), row_[i][k].get(), part.get());
        mpz_sub(row_[i][k].get(), row_[i][k].get(), origin.get());
      }
    }
  }

  /// The power of two that the rows' integers count in: row entry = integer * 2^scale().
  int scale() const { return lowest_; }

  /// The exponent of v's last significant place: v is an integer times 2^unitExponent(v).
  static int unitExponent(double v)
  {
    int e;
    std::frexp(v, &e);
    return e - 53;
  }

  /// v / 2^unit, an integer when unit <= unitExponent(v) (or v = 0).
  static void set(Integer& out, double v, int unit)
  {
    if (v == 0)
    {
      mpz_set_ui(out.get(), 0);
      return;
    }
    int e;
    const double m = std::frexp(v, &e);
    mpz_set_d(out.get(), std::ldexp(m, 53)); // an integer below 2^53: exact
    mpz_mul_2exp(out.get(), out.get(), static_cast<mp_bitcnt_t>(e - 53 - unit));
  }

  /// det[row i; row j; row k] = row i . (row j x row k).
  void minor3(int i, int j, int k, Integer& out)
  {
    mpz_set_ui(out.get(), 0);
    for (int c = 0; c < 3; ++c)
    {
      cross(j, k, c, t_);
      mpz_addmul(out.get(), row_[i][c].get(), t_.get());
    }
  }

  /// |row i|^2.
  void lift(int i, Integer& out)
  {
    mpz_mul(out.get(), row_[i][0].get(), row_[i][0].get());
    mpz_addmul(out.get(), row_[i][1].get(), row_[i][1].get());
    mpz_addmul(out.get(), row_[i][2].get(), row_[i][2].get());
  }

  /// Component c of row j x row k.
  void cross(int j, int k, int c, Integer& out)
  {
    const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
    mpz_mul(out.get(), row_[j][c1].get(), row_[k][c2].get());
    mpz_submul(out.get(), row_[j][c2].get(), row_[k][c1].get());
  }

  /// Whether row i and row j are parallel (or one is zero).
  bool parallel(int i, int j)
  {
    for (int c = 0; c < 3; ++c)
    {
      const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
      mpz_mul(t_.get(), row_[i][c1].get(), row_[j][c2].get());
      mpz_submul(t_.get(), row_[i][c2].get(), row_[j][c1].get());
      if (mpz_sgn(t_.get()) != 0)
        return false;
    }
    return true;
  }

private:
  Integer row_[N][3];
  Integer t_;
  int lowest_ = 0;
};
} // namespace

void exactSixVolume(const double* a, const double* b, const double* c, const double* d,
  double& mantissa, int& exponent)
{
  const double* const x[3] = {b, c, d};
  IntegerRows<3> rows(x, a);
  Integer det;
  rows.minor3(0, 1, 2, det);
  mpz_abs(det.get(), det.get());
  long e = 0;
  mantissa = mpz_get_d_2exp(&e, det.get());
  exponent = static_cast<int>(e) + 3 * rows.scale();
}

namespace
{
/// The highest binary scale 2^s at which every weight is an integer times 2^(2s) (weights are
/// squared lengths), or INT_MAX where all are 0.
int weightScaleLimit(const double* weights, int count)
{
  int unit = INT_MAX;
  for (int i = 0; i < count; ++i)
    if (weights[i] != 0)
      unit = std::min(unit, IntegerRows<4>::unitExponent(weights[i]));
  // floor(unit / 2), also for negative units.
  return unit == INT_MAX ? INT_MAX : (unit >= 0 ? unit / 2 : -((1 - unit) / 2));
}

/// insphere's sign from the integer rows x - e of q: det[(x - e, lift)] expanded along the lift
/// column, each lift |x - e|^2, lowered by w_x - w_e where `weights` (of the rows, then of e) are
/// given, counted at twice the rows' scale (which weightScaleLimit() made low enough).
int liftedDeterminantSign(IntegerRows<4>& q, const double* weights = nullptr)
{
  const int weightScale = 2 * q.scale();
  Integer det, lift, minor, weight, weightE;
  if (weights)
    IntegerRows<4>::set(weightE, weights[4], weightScale);
  const int others[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  const int sign[4] = {-1, 1, -1, 1};
  for (int r = 0; r < 4; ++r)
  {
    q.lift(r, lift);
    if (weights)
    {
      IntegerRows<4>::set(weight, weights[r], weightScale);
      mpz_sub(lift.get(), lift.get(), weight.get());
      mpz_add(lift.get(), lift.get(), weightE.get());
    }
    q.minor3(others[r][0], others[r][1], others[r][2], minor);
    if (sign[r] > 0)
      mpz_addmul(det.get(), lift.get(), minor.get());
    else
      mpz_submul(det.get(), lift.get(), minor.get());
  }
  return -mpz_sgn(det.get());
}
} // namespace

bool exactCircumcentreOffset(const double* a, const double* b, const double* c, const double* d,
  double offset[3], const double* weights)
{
  // With rows u, v, w = (b, c, d) - a: offset = (|u|^2 v x w + |v|^2 w x u + |w|^2 u x v) /
  // (2 u . v x w), each integer row counting 2^scale: the numerator counts 2^(4 scale) and the
  // denominator 2^(3 scale). Weighted, each |row|^2 is lowered by its weight less a's, which
  // counts 2^(2 scale) too.
  const double* const x[3] = {b, c, d};
  IntegerRows<3> rows(x, a, weights ? weightScaleLimit(weights, 4) : INT_MAX);
  Integer det, lift[3], term, numerator, weight, weightA;
  rows.minor3(0, 1, 2, det);
  if (mpz_sgn(det.get()) == 0)
    return false;
  if (weights)
    IntegerRows<3>::set(weightA, weights[0], 2 * rows.scale());
  for (int i = 0; i < 3; ++i)
  {
    rows.lift(i, lift[i]);
    if (weights)
    {
      IntegerRows<3>::set(weight, weights[i + 1], 2 * rows.scale());
      mpz_sub(lift[i].get(), lift[i].get(), weight.get());
      mpz_add(lift[i].get(), lift[i].get(), weightA.get());
    }
  }
  long denominatorExponent = 0;
  const double denominator = mpz_get_d_2exp(&denominatorExponent, det.get());
  for (int k = 0; k < 3; ++k)
  {
    mpz_set_ui(numerator.get(), 0);
    for (int i = 0; i < 3; ++i)
    {
      rows.cross((i + 1) % 3, (i + 2) % 3, k, term);
      mpz_addmul(numerator.get(), lift[i].get(), term.get());
    }
    long numeratorExponent = 0;
    const double n = mpz_get_d_2exp(&numeratorExponent, numerator.get());
    offset[k] = std::ldexp(n / denominator,
      static_cast<int>(numeratorExponent - denominatorExponent - 1 + rows.scale()));
  }
  return true;
}

void Predicates::adaptTo(
  const double* xyz, std::size_t count, std::size_t stride, const Bounds& box)
{
  tuning_ = Tuning();
  setBoxBounds(box);
  include(xyz, count, stride);
}

void Predicates::widenTo(const Bounds& box)
{
  setBoxBounds(box);
  applyGrid();
}

void Predicates::setBoxBounds(const Bounds& box)
{
  for (int k = 0; k < 3; ++k)
    tuning_.extents[k] = box.extent(k);
  tuning_.magnitude = std::max({std::fabs(box.lo[0]), std::fabs(box.lo[1]), std::fabs(box.lo[2]),
    std::fabs(box.hi[0]), std::fabs(box.hi[1]), std::fabs(box.hi[2])});
  applyBoxBounds();
}

void Predicates::applyBoxBounds()
{
  // Static bounds: the semi-static ones with every difference at its largest possible value, the
  // box's extent on its axis (the 1% covers the rounding of the extents and of the differences).
  // Per axis, not the largest extent cubed: flat sets (terrain, slabs) get bounds as tight as
  // their thickness allows. Tiny extents, where products could underflow, keep the semi-static
  // filter with its underflow guard.
  const double* e = tuning_.extents;
  // Records of images (useImages()) are within u |x| of the exact coordinates, so the differences
  // of the exact points are within eps = 2 u M of the records', M the largest |x| (1% for the
  // rounding of M).
  tuning_.imageSlack = tuning_.images ? 2 * filter::kEpsilon * tuning_.magnitude * 1.01 : 0.0;
  const double eps = tuning_.imageSlack;
  const double orientProduct = (e[0] + eps) * (e[1] + eps) * (e[2] + eps);
  const double m = std::max({e[0], e[1], e[2]}) + eps;
  const bool staticSafe = !tuning_.anyMagnitude && orientProduct > filter::kUnderflowGuard &&
    m * m * orientProduct > filter::kUnderflowGuard;
  const filter::RecordBounds bounds = filter::recordBounds(e, eps);
  tuning_.boxOrient = staticSafe ? bounds.orient : HUGE_VAL;
  tuning_.boxInSphere = staticSafe ? bounds.inSphere : HUGE_VAL;
}

void Predicates::useImages(const PeriodicImages* images)
{
  tuning_.images = images;
  liftsFirst_ = false;
  applyBoxBounds();
  applyGrid();
}

void Predicates::adaptToWeights(double lowest, double highest)
{
  const double* e = tuning_.extents;
  const double m = std::max({e[0], e[1], e[2]}), spread = highest - lowest;
  const double scale = e[0] * e[1] * e[2] * (3 * m * m + spread);
  // The extents bound every difference of coordinates, the spread every difference of weights;
  // 1% for the rounding of both. Products of the normal range keep the relative bounds.
  const bool safe = !tuning_.anyMagnitude && scale > filter::kUnderflowGuard && scale < 0x1p900 &&
    std::isfinite(spread);
  // Images' records (useImages()) widen the differences by the slack of their rounding.
  const double bound = tuning_.images ? filter::powerRecordBound(e, spread, tuning_.imageSlack)
                                      : filter::kPowerSemiStatic * scale * 1.01;
  tuning_.powerStatic = safe ? bound : HUGE_VAL;
}

void Predicates::include(const double* xyz, std::size_t count, std::size_t stride)
{
  int& lowest = tuning_.lowest;
  int& highest = tuning_.highest;
  for (std::size_t i = 0; i < 3 * count && lowest != Tuning::kNoGrid; ++i)
  {
    const double x = xyz[i / 3 * stride + i % 3];
    if (x == 0.0)
      continue;
    int exponent;
    const double mantissa = std::frexp(x, &exponent);
    // The lowest set bit of the 53-bit significand gives the finest grid this value needs.
    const auto significand = static_cast<std::uint64_t>(std::ldexp(std::fabs(mantissa), 53));
    lowest = std::min(lowest, exponent - 53 + countTrailingZeros(significand));
    highest = std::max(highest, exponent);
    if (highest - lowest > kIntegerGridBits)
      lowest = Tuning::kNoGrid;
  }
  applyGrid();
}

void Predicates::allowAnyMagnitude()
{
  tuning_.anyMagnitude = true;
  tuning_.boxOrient = tuning_.boxInSphere = HUGE_VAL;
  liftsFirst_ = false;
  applyGrid();
}

void Predicates::applyGrid()
{
  Tuning& t = tuning_;
  if (t.images)
  {
    // The records' grid is not the exact images'.
    t.inverseGridUnit = 0.0;
    t.floatExactOrient = t.floatExactInSphere = false;
    t.orientStatic = t.boxOrient;
    t.inSphereStatic = t.boxInSphere;
    t.powerStatic = HUGE_VAL;
    return;
  }
  if (t.anyMagnitude)
  {
    t.inverseGridUnit = 0.0;
    t.floatExactOrient = t.floatExactInSphere = false;
    t.orientStatic = t.inSphereStatic = t.powerStatic = HUGE_VAL;
    return;
  }
  const bool onGrid = t.lowest != Tuning::kNoGrid && t.lowest <= t.highest;
  const int gridBits = onGrid ? t.highest - t.lowest : kIntegerGridBits + 1;
#ifdef FD3_HAVE_INT128
  t.inverseGridUnit = onGrid ? std::ldexp(1.0, -t.lowest) : 0.0;
#else
  t.inverseGridUnit = 0.0; // no 128-bit integers: the exact stage uses expansions
#endif
  // On a grid of b bits, differences are integers (in units of u) below 2^(b+1). orient3d's
  // products, minors and sum then stay below 2^(3b+6) <= 2^51, and insphere's 2x2 minors below
  // 2^(2b+3), 3x3 minors below 2^(3b+6), lifts below 2^(2b+4) and determinant below
  // 2^(5b+12) <= 2^52: every float operation is exact, provided no product of five values leaves
  // the normal range (always so for points normalized into [-1, 1]).
  const bool normalProducts = onGrid && t.lowest > -190 && t.highest < 190;
  t.floatExactOrient = normalProducts && gridBits <= kFloatExactOrientBits;
  t.floatExactInSphere = normalProducts && gridBits <= kFloatExactInSphereBits;
  t.orientStatic = t.floatExactOrient ? 0 : t.boxOrient;
  t.inSphereStatic = t.floatExactInSphere ? 0 : t.boxInSphere;
}

// On the grid, coordinates are integers below 2^23 in magnitude, so differences are exact doubles
// and integers below 2^24: 2x2 minors stay below 2^49, 3x3 minors (orient3d) below 3 * 2^73, lifts
// below 3 * 2^48, and the insphere determinant, four products of a lift and a 3x3 minor, below
// 36 * 2^123 < 2^127 -- all exact in 128-bit integers.
template <int N>
void Predicates::gridDifferences(
  const double* const x[N], const double* y, std::int64_t out[N][3]) const
{
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < 3; ++k)
      out[i][k] = static_cast<std::int64_t>((x[i][k] - y[k]) * tuning_.inverseGridUnit);
}

namespace
{
/// The axis on which the four points have one coordinate, exactly: they lie in a plane
/// perpendicular to it. -1 when there is none.
int sharedAxis(const double* const p[4])
{
  for (int k = 0; k < 3; ++k)
    if (p[0][k] == p[1][k] && p[0][k] == p[2][k] && p[0][k] == p[3][k])
      return k;
  return -1;
}
/// The five points but five[off], in order.
void allBut(const double* const five[5], int off, const double* four[4])
{
  for (int i = 0, j = 0; i < 5; ++i)
    if (i != off)
      four[j++] = five[i];
}

/// Whether p and q differ in coordinate k alone.
bool differOnlyIn(const double* p, const double* q, int k)
{
  return p[(k + 1) % 3] == q[(k + 1) % 3] && p[(k + 2) % 3] == q[(k + 2) % 3];
}

/// Whether the four points are the corners of a rectangle two of whose sides are parallel to an
/// axis: two pairs that differ in coordinate k alone, at the same two values of it (the cells of
/// an extruded profile or of a structured grid's face). Such points are coplanar and cocircular,
/// so every insphere determinant of them and a fifth point is 0, and so is their orientation.
bool formAxisRectangle(const double* const p[4])
{
  constexpr int kPairings[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};
  for (const auto& pairing : kPairings)
  {
    const double *a = p[pairing[0]], *a2 = p[pairing[1]], *b = p[pairing[2]], *b2 = p[pairing[3]];
    for (int k = 0; k < 3; ++k)
      if (differOnlyIn(a, a2, k) && differOnlyIn(b, b2, k) &&
        ((a[k] == b[k] && a2[k] == b2[k]) || (a[k] == b2[k] && a2[k] == b[k])))
        return true;
  }
  return false;
}

/// How many of the 10 pairs of five points share each coordinate, and how many share two, in one
/// pass of comparisons: the structures below need several shared coordinates, so most calls stop
/// here.
struct SharedCoordinates
{
  explicit SharedCoordinates(const double* const five[5])
  {
    for (int i = 0; i < 5; ++i)
      for (int j = i + 1; j < 5; ++j)
      {
        const int x = five[i][0] == five[j][0], y = five[i][1] == five[j][1],
                  z = five[i][2] == five[j][2];
        onAxis[0] += x;
        onAxis[1] += y;
        onAxis[2] += z;
        onTwoAxes += x + y + z >= 2;
      }
  }
  /// Four points in a plane x_k = v share x_k in all 6 of their pairs.
  bool mayShareAxis() const { return onAxis[0] >= 6 || onAxis[1] >= 6 || onAxis[2] >= 6; }
  /// An axis-parallel rectangle has 2 pairs of corners that share two coordinates.
  bool mayFormRectangle() const { return onTwoAxes >= 2; }
  int onAxis[3] = {0, 0, 0};
  int onTwoAxes = 0;
};

/// Whether x is 0 or of a magnitude within 2^-200..2^200.
bool moderate(double x)
{
  const double m = std::fabs(x);
  return m == 0 || (m >= 0x1p-200 && m <= 0x1p200);
}

/// Whether four of the five points form an axis-parallel rectangle (formAxisRectangle()): the
/// structured samples' ties, settled without arithmetic.
bool fourFormAxisRectangle(const double* const five[5])
{
  for (int off = 0; off < 5; ++off)
  {
    const double* four[4];
    allBut(five, off, four);
    if (formAxisRectangle(four))
      return true;
  }
  return false;
}
} // namespace

Expansion Predicates::minor3(Expansion const u[3], Expansion const v[3], Expansion const w[3])
{
  ExpansionArena& x = arena_;
  // u . (v x w)
  const Expansion cx = x.subtract(x.multiply(v[1], w[2]), x.multiply(v[2], w[1]));
  const Expansion cy = x.subtract(x.multiply(v[2], w[0]), x.multiply(v[0], w[2]));
  const Expansion cz = x.subtract(x.multiply(v[0], w[1]), x.multiply(v[1], w[0]));
  return x.add(x.add(x.multiply(u[0], cx), x.multiply(u[1], cy)), x.multiply(u[2], cz));
}

int Predicates::orient3dBeyondStatic(
  double det, const double* a, const double* b, const double* c, const double* d)
{
  if (tuning_.floatExactOrient)
    return 0;
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  // Semi-static filter: the permanent is at most 6 times the product of the largest |x|, |y| and
  // |z| differences, so Shewchuk's bound (7 + 56 eps) eps * permanent is below
  // filter::kOrientSemiStatic times that product. For images with rounded records, the bound
  // widened by how far the exact differences may lie from the records' (filter::recordBounds()).
  const double largest[3] = {std::max({std::fabs(adx), std::fabs(bdx), std::fabs(cdx)}),
    std::max({std::fabs(ady), std::fabs(bdy), std::fabs(cdy)}),
    std::max({std::fabs(adz), std::fabs(bdz), std::fabs(cdz)})};
  const double scale = largest[0] * largest[1] * largest[2];
  const bool inexact = tuning_.images && anyInexact(a, b, c, d);
  const double bound = inexact ? filter::recordBounds(largest, tuning_.imageSlack).orient
                               : filter::kOrientSemiStatic * scale;
  if ((det > bound || -det > bound) && semiStaticHolds(scale, filter::kOrientRange, largest))
    return -filter::signOf(det);
  return inexact ? orient3dOfImages(a, b, c, d) : orient3dExact(a, b, c, d);
}

int Predicates::orient3dExact(const double* a, const double* b, const double* c, const double* d)
{
  ++exactOrientCalls;
  // Structured samples (grid faces, layers, rings) are full of these, and the expansions would
  // take a hundred times as long to find the zero.
  const double* points[4] = {a, b, c, d};
  if (sharedAxis(points) >= 0 || formAxisRectangle(points))
    return 0;
  if (tuning_.anyMagnitude)
  {
    ++integerExactCalls;
    const double* rows[3] = {b, c, d};
    IntegerRows<3> q(rows, a);
    Integer det;
    q.minor3(0, 1, 2, det);
    return mpz_sgn(det.get());
  }
#ifdef FD3_HAVE_INT128
  if (tuning_.inverseGridUnit > 0)
  {
    const double* rows[3] = {b, c, d};
    std::int64_t q[3][3];
    gridDifferences<3>(rows, a, q);
    return signOf(det3(q[0], q[1], q[2]));
  }
#endif
  arena_.reset();
  Expansion u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = arena_.fromDifference(b[k], a[k]);
    v[k] = arena_.fromDifference(c[k], a[k]);
    w[k] = arena_.fromDifference(d[k], a[k]);
  }
  return minor3(u, v, w).sign();
}

bool Predicates::insideBeyondFirstFilter(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  double lifts[4];
  const double det = inSphereDeterminant(a, b, c, d, e, lifts);
  int s = inSphereFiltered(det, lifts, a, b, c, d, e);
  if (s == 0 && !tuning_.floatExactInSphere)
    s = inSphereDoubleDouble(a, b, c, d, e);
  const double* const p[4] = {a, b, c, d};
  return (s != 0 ? s : symbolicInSphere(p, e)) > 0;
}

// The insphere determinant over exact differences (each a double-double), in double-double
// arithmetic, decided when it clears its error bound; else the exact stage. Points on an integer
// grid go straight to the exact stage, which is as cheap there and also settles exact ties.
int Predicates::inSphereDoubleDouble(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  if (tuning_.images && anyInexact(a, b, c, d, e))
  {
    if (const int sign = inSphereOfImagesDoubleDouble(a, b, c, d, e); sign != kUndecided)
      return sign;
    return inSphereOfImages(a, b, c, d, e);
  }
  if (tuning_.inverseGridUnit > 0)
    return inSphereExact(a, b, c, d, e);
  const double* five[5] = {a, b, c, d, e};
  const SharedCoordinates shared(five);
  if (shared.mayFormRectangle() && fourFormAxisRectangle(five))
    return 0;
  if (tuning_.anyMagnitude)
    return inSphereExact(a, b, c, d, e);
  if (shared.mayShareAxis())
    if (const int sign = inSphereOnAxisPlane(five); sign != kUndecided)
      return sign;
  const double* rows[4] = {a, b, c, d};
  ++doubleDoubleInSphereCalls;
  DoubleDouble x[4][3];
  double m[4][3]; // |x|, for the permanent
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < 3; ++k)
    {
      x[r][k] = DoubleDouble::difference(rows[r][k], e[k]);
      m[r][k] = std::fabs(x[r][k].hi);
    }
  if (const int sign = inSphereOfDifferences(x, m, kInSphereDoubleDouble); sign != kUndecided)
    return sign;
  return inSphereExact(a, b, c, d, e);
}

int Predicates::inSphereOfImagesDoubleDouble(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  const double* rows[4] = {a, b, c, d};
  const double* residualE = residualOrNone(e);
  ++doubleDoubleInSphereCalls;
  DoubleDouble x[4][3];
  double m[4][3]; // |records' difference| + |residuals' difference|, for the permanent
  for (int r = 0; r < 4; ++r)
  {
    const double* residual = residualOrNone(rows[r]);
    for (int k = 0; k < 3; ++k)
    {
      const DoubleDouble records = DoubleDouble::difference(rows[r][k], e[k]);
      const DoubleDouble residuals = DoubleDouble::difference(residual[k], residualE[k]);
      x[r][k] = records + residuals;
      m[r][k] = std::fabs(records.hi) + std::fabs(records.lo) + std::fabs(residuals.hi) +
        std::fabs(residuals.lo);
    }
  }
  return inSphereOfDifferences(x, m, kInSphereImagesDoubleDouble);
}

int Predicates::inSphereOfDifferences(
  const DoubleDouble x[4][3], const double m[4][3], double coefficient) const
{
  // 2x2 minors of the x and y columns, rows (i, j).
  auto minor2 = [&](int i, int j) { return x[i][0] * x[j][1] - x[j][0] * x[i][1]; };
  auto minor2Permanent = [&](int i, int j) { return m[i][0] * m[j][1] + m[j][0] * m[i][1]; };
  const DoubleDouble ab = minor2(0, 1), bc = minor2(1, 2), cd = minor2(2, 3), da = minor2(3, 0),
                     ac = minor2(0, 2), bd = minor2(1, 3);
  const double abP = minor2Permanent(0, 1), bcP = minor2Permanent(1, 2),
               cdP = minor2Permanent(2, 3), daP = minor2Permanent(3, 0),
               acP = minor2Permanent(0, 2), bdP = minor2Permanent(1, 3);
  // 3x3 minors with the z column, as in the float evaluation (Predicates.h).
  const DoubleDouble abc = x[0][2] * bc - x[1][2] * ac + x[2][2] * ab;
  const DoubleDouble bcd = x[1][2] * cd - x[2][2] * bd + x[3][2] * bc;
  const DoubleDouble cda = x[2][2] * da + x[3][2] * ac + x[0][2] * cd;
  const DoubleDouble dab = x[3][2] * ab + x[0][2] * bd + x[1][2] * da;
  const double abcP = m[0][2] * bcP + m[1][2] * acP + m[2][2] * abP;
  const double bcdP = m[1][2] * cdP + m[2][2] * bdP + m[3][2] * bcP;
  const double cdaP = m[2][2] * daP + m[3][2] * acP + m[0][2] * cdP;
  const double dabP = m[3][2] * abP + m[0][2] * bdP + m[1][2] * daP;
  DoubleDouble lift[4];
  double liftP[4];
  for (int r = 0; r < 4; ++r)
  {
    lift[r] = x[r][0] * x[r][0] + x[r][1] * x[r][1] + x[r][2] * x[r][2];
    liftP[r] = m[r][0] * m[r][0] + m[r][1] * m[r][1] + m[r][2] * m[r][2];
  }
  const DoubleDouble det = (lift[3] * abc - lift[2] * dab) + (lift[1] * cda - lift[0] * bcd);
  const double permanent =
    (liftP[3] * abcP + liftP[2] * dabP) + (liftP[1] * cdaP + liftP[0] * bcdP);
  const double value = det.value();
  const double bound = coefficient * permanent;
  if ((value > bound || -value > bound) && permanent > kDoubleDoubleSmallest)
    return -signOf(value);
  return kUndecided;
}

int Predicates::inSphereExact(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  ++exactInSphereCalls;
#ifdef FD3_HAVE_INT128
  if (tuning_.inverseGridUnit > 0)
  {
    const double* rows[4] = {a, b, c, d};
    std::int64_t q[4][3];
    gridDifferences<4>(rows, e, q);
    Int128 lift[4];
    for (int r = 0; r < 4; ++r)
      lift[r] = Int128(q[r][0]) * q[r][0] + Int128(q[r][1]) * q[r][1] + Int128(q[r][2]) * q[r][2];
    const Int128 det = lift[1] * det3(q[0], q[2], q[3]) - lift[0] * det3(q[1], q[2], q[3]) +
      lift[3] * det3(q[0], q[1], q[2]) - lift[2] * det3(q[0], q[1], q[3]);
    return -signOf(det);
  }
#endif
  const double* rows[4] = {a, b, c, d};
  if (tuning_.anyMagnitude)
  {
    ++integerExactCalls;
    IntegerRows<4> q(rows, e);
    return liftedDeterminantSign(q);
  }
  ExpansionArena& x = arena_;
  x.reset();
  Expansion diff[4][3], lift[4];
  for (int r = 0; r < 4; ++r)
  {
    for (int k = 0; k < 3; ++k)
      diff[r][k] = x.fromDifference(rows[r][k], e[k]);
    lift[r] = x.add(x.add(x.multiply(diff[r][0], diff[r][0]), x.multiply(diff[r][1], diff[r][1])),
      x.multiply(diff[r][2], diff[r][2]));
  }
  // Laplace expansion along the lift column of det[(x-e, |x-e|^2)].
  const Expansion m0 = minor3(diff[1], diff[2], diff[3]);
  const Expansion m1 = minor3(diff[0], diff[2], diff[3]);
  const Expansion m2 = minor3(diff[0], diff[1], diff[3]);
  const Expansion m3 = minor3(diff[0], diff[1], diff[2]);
  const Expansion det = x.add(x.subtract(x.multiply(lift[1], m1), x.multiply(lift[0], m0)),
    x.subtract(x.multiply(lift[3], m3), x.multiply(lift[2], m2)));
  return -det.sign();
}

int Predicates::powerTest(const double* const p[4], const double* pe, const double w[4], double we)
{
  double d[4][3], lift[4], largest[3] = {0, 0, 0}, largestWeight = 0;
  for (int r = 0; r < 4; ++r)
  {
    for (int k = 0; k < 3; ++k)
    {
      d[r][k] = p[r][k] - pe[k];
      largest[k] = std::max(largest[k], std::fabs(d[r][k]));
    }
    const double dw = w[r] - we;
    largestWeight = std::max(largestWeight, std::fabs(dw));
    lift[r] = (d[r][0] * d[r][0] + d[r][1] * d[r][1] + d[r][2] * d[r][2]) - dw;
  }
  auto minor3 = [&](int i, int j, int k) {
    return d[i][0] * (d[j][1] * d[k][2] - d[j][2] * d[k][1]) +
      d[i][1] * (d[j][2] * d[k][0] - d[j][0] * d[k][2]) +
      d[i][2] * (d[j][0] * d[k][1] - d[j][1] * d[k][0]);
  };
  // Laplace expansion along the lift column of det[(x - e, lift)], as in inSphereExact().
  const double det = (lift[1] * minor3(0, 2, 3) - lift[0] * minor3(1, 2, 3)) +
    (lift[3] * minor3(0, 1, 2) - lift[2] * minor3(0, 1, 3));
  const double m = std::max({largest[0], largest[1], largest[2]});
  const double scale = largest[0] * largest[1] * largest[2] * (3 * m * m + largestWeight);
  const bool inexact = tuning_.images && anyInexact(p[0], p[1], p[2], p[3], pe);
  const double bound = inexact
    ? filter::powerRecordBound(largest, largestWeight, tuning_.imageSlack)
    : filter::kPowerSemiStatic * scale;
  // An overflow leaves det or the bound infinite or NaN: no comparison then holds.
  if ((det > bound || -det > bound) && semiStaticHolds(scale, filter::kInSphereRange, largest))
    return -signOf(det);
  return powerTestExact(p, pe, w, we);
}

// Over integers: the coordinates count a power of two 2^s low enough that the weights, which are
// squared lengths, are integers times 2^(2s).
int Predicates::powerTestExact(
  const double* const p[4], const double* pe, const double w[4], double we)
{
  ++exactInSphereCalls;
  ++integerExactCalls;
  const double weights[5] = {w[0], w[1], w[2], w[3], we};
  const double* residuals[4] = {nullptr, nullptr, nullptr, nullptr};
  const double* residualE = nullptr;
  if (tuning_.images)
  {
    for (int r = 0; r < 4; ++r)
      residuals[r] = residualOf(p[r]);
    residualE = residualOf(pe);
  }
  IntegerRows<4> q(p, pe, residuals, residualE, weightScaleLimit(weights, 5));
  return liftedDeterminantSign(q, weights);
}

// Four of the five points in a plane x_k = v: expanding the homogeneous 5x5 form of the
// determinant, det[(p, |p|^2, 1)] (which equals the 4x4 one relative to e), along column k after
// moving the plane to v = 0 leaves (-1)^(r + k) w times the 4x4 homogeneous incircle determinant
// of the four in the plane, r being the row of the fifth point and w its distance from the plane.
// So the sign takes a comparison and an exact 2D incircle test, of degree 4 in 2 dimensions
// where the 3D test has degree 5 in 3. The caller has settled the rectangles among them already.
int Predicates::inSphereOnAxisPlane(const double* const five[5])
{
  for (int off = 0; off < 5; ++off)
  {
    const double* plane[4];
    allBut(five, off, plane);
    const int k = sharedAxis(plane);
    if (k < 0)
      continue;
    const int u = k == 0 ? 1 : 0, v = k == 2 ? 1 : 2;    // the other axes, in order
    const int side = signOf(five[off][k] - plane[0][k]); // exact: a difference keeps its sign
    return ((off + k) % 2 ? 1 : -1) * side * inCircle(plane, u, v);
  }
  return kUndecided;
}

// det[(q - s, |q - s|^2) for q in the first three] in the axes u < v, s the fourth point: the
// homogeneous 4x4 determinant det[(q_u, q_v, q_u^2 + q_v^2, 1)] of the four. In floats first,
// under Shewchuk's bound for incircle, (10 + 96 eps) eps times the permanent.
int Predicates::inCircle(const double* const p[4], int u, int v)
{
  double fu[3], fv[3], fl[3], mu[3], mv[3];
  for (int i = 0; i < 3; ++i)
  {
    fu[i] = p[i][u] - p[3][u];
    fv[i] = p[i][v] - p[3][v];
    fl[i] = fu[i] * fu[i] + fv[i] * fv[i];
    mu[i] = std::fabs(fu[i]);
    mv[i] = std::fabs(fv[i]);
  }
  const double value = fl[0] * (fu[1] * fv[2] - fu[2] * fv[1]) -
    fl[1] * (fu[0] * fv[2] - fu[2] * fv[0]) + fl[2] * (fu[0] * fv[1] - fu[1] * fv[0]);
  const double permanent = fl[0] * (mu[1] * mv[2] + mu[2] * mv[1]) +
    fl[1] * (mu[0] * mv[2] + mu[2] * mv[0]) + fl[2] * (mu[0] * mv[1] + mu[1] * mv[0]);
  const double bound = filter::kInCircle * permanent;
  if ((value > bound || -value > bound) && permanent > filter::kUnderflowGuard)
    return signOf(value);
  // Then in double-double, on the exact differences, as inSphereDoubleDouble().
  DoubleDouble du[3], dv[3], lift[3];
  for (int i = 0; i < 3; ++i)
  {
    du[i] = DoubleDouble::difference(p[i][u], p[3][u]);
    dv[i] = DoubleDouble::difference(p[i][v], p[3][v]);
    lift[i] = du[i] * du[i] + dv[i] * dv[i];
  }
  auto minor2 = [&](int i, int j) { return du[i] * dv[j] - du[j] * dv[i]; };
  const double refined =
    (lift[0] * minor2(1, 2) - lift[1] * minor2(0, 2) + lift[2] * minor2(0, 1)).value();
  const double refinedBound = kInCircleDoubleDouble * permanent;
  if ((refined > refinedBound || -refined > refinedBound) && permanent > kDoubleDoubleSmallest)
    return signOf(refined);
  return inCircleExact(p, u, v);
}

int Predicates::inCircleExact(const double* const p[4], int u, int v)
{
  ExpansionArena& x = arena_;
  x.reset();
  Expansion du[3], dv[3], lift[3];
  for (int i = 0; i < 3; ++i)
  {
    du[i] = x.fromDifference(p[i][u], p[3][u]);
    dv[i] = x.fromDifference(p[i][v], p[3][v]);
    lift[i] = x.add(x.multiply(du[i], du[i]), x.multiply(dv[i], dv[i]));
  }
  auto minor2 = [&](int i, int j) {
    return x.subtract(x.multiply(du[i], dv[j]), x.multiply(du[j], dv[i]));
  };
  const Expansion det =
    x.add(x.subtract(x.multiply(lift[0], minor2(1, 2)), x.multiply(lift[1], minor2(0, 2))),
      x.multiply(lift[2], minor2(0, 1)));
  return det.sign();
}

int Predicates::orient3dOfImages(const double* a, const double* b, const double* c, const double* d)
{
  ++exactOrientCalls;
  const double* const points[4] = {a, b, c, d};
  const double* residuals[4];
  bool expansionsHold = true; // every term's product within the doubles' normal range
  for (int r = 0; r < 4; ++r)
  {
    residuals[r] = residualOrNone(points[r]);
    for (int k = 0; k < 3; ++k)
      expansionsHold = expansionsHold && moderate(points[r][k]) && moderate(residuals[r][k]);
  }
  if (expansionsHold)
  {
    // Each difference the records' and the residuals' exact differences added; the parts of a
    // difference of numbers within 2^-200..2^200 lie within 2^-253..2^201, so the minor's
    // products of three neither under- nor overflow.
    const double* residualA = residuals[0];
    const double* const rows[3] = {b, c, d};
    arena_.reset();
    Expansion x[3][3];
    for (int r = 0; r < 3; ++r)
    {
      const double* residual = residuals[r + 1];
      for (int k = 0; k < 3; ++k)
        x[r][k] = arena_.add(arena_.fromDifference(rows[r][k], a[k]),
          arena_.fromDifference(residual[k], residualA[k]));
    }
    return minor3(x[0], x[1], x[2]).sign();
  }
  ++integerExactCalls;
  const double* rows[3] = {b, c, d};
  const double* rowResiduals[3] = {residuals[1], residuals[2], residuals[3]};
  IntegerRows<3> q(rows, a, rowResiduals, residuals[0]);
  Integer det;
  q.minor3(0, 1, 2, det);
  return mpz_sgn(det.get());
}

const double* Predicates::residualOrNone(const double* p) const
{
  const double* residual = residualOf(p);
  return residual ? residual : kNoResidual;
}

int Predicates::inSphereOfImages(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  ++exactInSphereCalls;
  ++integerExactCalls;
  const double* rows[4] = {a, b, c, d};
  const double* residuals[4] = {residualOf(a), residualOf(b), residualOf(c), residualOf(d)};
  IntegerRows<4> q(rows, e, residuals, residualOf(e));
  return liftedDeterminantSign(q);
}

bool Predicates::collinearOfImages(const double* a, const double* b, const double* c)
{
  const double* rows[2] = {b, c};
  const double* residuals[2] = {residualOf(b), residualOf(c)};
  return IntegerRows<2>(rows, a, residuals, residualOf(a)).parallel(0, 1);
}

bool Predicates::collinear(const double* a, const double* b, const double* c)
{
  if (tuning_.images && anyInexact(a, b, c))
    return collinearOfImages(a, b, c);
  if (tuning_.anyMagnitude)
  {
    const double* rows[2] = {b, c};
    return IntegerRows<2>(rows, a).parallel(0, 1);
  }
  arena_.reset();
  Expansion u[3], v[3];
  for (int k = 0; k < 3; ++k)
  {
    u[k] = arena_.fromDifference(b[k], a[k]);
    v[k] = arena_.fromDifference(c[k], a[k]);
  }
  for (int k = 0; k < 3; ++k)
  {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Expansion cross =
      arena_.subtract(arena_.multiply(u[i], v[j]), arena_.multiply(u[j], v[i]));
    if (cross.sign() != 0)
      return false;
  }
  return true;
}

// A tie of inSphere between the positive tetrahedron `tet` (points p) and point e (at pe), broken.
int Predicates::symbolicInSphere(const double* const p[4], const double* pe)
{
  ++symbolicTies;
  // The keys are computed here, not stored with the vertices, which have no room left for them:
  // most inputs tie rarely. Periodic images carry theirs, and go in their own order, the same for
  // every translate of a configuration.
  ImageOf image[5];
  const double* const five[5] = {p[0], p[1], p[2], p[3], pe};
  for (int i = 0; i < 5; ++i)
  {
    const ImageOf* found = tuning_.images ? tuning_.images->find(five[i]) : nullptr;
    if (found)
      image[i] = *found;
    else
    {
      image[i] = ImageOf{{0, 0, 0}, {five[i][0], five[i][1], five[i][2]}, {0, 0, 0},
        perturbationKey(five[i], perturbationSeed_)};
    }
  }
  auto before = [&image](int i, int j) { return precedes(image[i], image[j]); };
  // Lowering the lift of point v by delta_v changes (plane - lift)(e) by
  //   delta_e - sum_{v in tet} delta_v * lambda_v(e),
  // lambda_v(e) being the barycentric coordinate of e, whose sign is orient3d(tet with v := e).
  // The term of the first point in the perturbation's order dominates; the first non-zero one
  // decides.
  std::uint32_t done = 0; // bit k: vertex k's term was zero
  for (int round = 0; round < 4; ++round)
  {
    int k = -1;
    for (int i = 0; i < 4; ++i)
      if (!(done >> i & 1u) && (k < 0 || before(i, k)))
        k = i;
    if (before(4, k))
      return 1;
    const double* q[4] = {p[0], p[1], p[2], p[3]};
    q[k] = pe;
    const int o = orient3d(q[0], q[1], q[2], q[3]);
    if (o != 0)
      return -o;
    done |= 1u << k;
  }
  return 1; // e comes last: its own lowering decides
}

} // namespace fd3
