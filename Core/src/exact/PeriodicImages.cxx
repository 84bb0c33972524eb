#include "exact/PeriodicImages.h"

#include "exact/Expansion.h"

#include <gmp.h>

#include <algorithm>
#include <cmath>

namespace fd3
{
namespace
{
/// v = m 2^e with an integer m below 2^53 in magnitude.
void toInteger(double v, mpz_t m, long& e)
{
  int exponent = 0;
  const double mantissa = std::frexp(v, &exponent);
  mpz_set_d(m, std::ldexp(mantissa, 53));
  e = exponent - 53;
}
} // namespace

bool translateExactly(
  double x, std::int64_t periods, double period, double& rounded, double& residual)
{
  // periods * period is usually a double (one or two periods; any power of two), and then the
  // error-free sum of two doubles gives the answer.
  const double shift = static_cast<double>(periods) * period;
  if (static_cast<std::int64_t>(static_cast<double>(periods)) == periods &&
    std::fma(static_cast<double>(periods), period, -shift) == 0)
  {
    twoSum(x, shift, rounded, residual);
    return std::isfinite(rounded) && std::isfinite(residual);
  }
  // Else in integers, at the finer of the two units: v = x + periods * period.
  mpz_t mx, mp, v, h, r, half;
  mpz_inits(mx, mp, v, h, r, half, nullptr);
  long ex = 0, ep = 0;
  toInteger(x, mx, ex);
  toInteger(period, mp, ep);
  const long unit = std::min(ex, ep);
  mpz_mul_2exp(mx, mx, static_cast<mp_bitcnt_t>(ex - unit));
  mpz_mul_2exp(mp, mp, static_cast<mp_bitcnt_t>(ep - unit));
  mpz_set_si(h, static_cast<long>(periods));
  mpz_mul(v, mp, h);
  mpz_add(v, v, mx);
  // Rounded to nearest, ties to even: the top 53 bits, and one unit more where the rest is over
  // half of it.
  const long bits = static_cast<long>(mpz_sizeinbase(v, 2));
  const long drop = mpz_sgn(v) == 0 ? 0 : std::max(0L, bits - 53);
  mpz_tdiv_q_2exp(h, v, static_cast<mp_bitcnt_t>(drop));
  mpz_mul_2exp(h, h, static_cast<mp_bitcnt_t>(drop));
  mpz_sub(r, v, h); // the sign of v, below one unit 2^drop
  if (drop > 0)
  {
    mpz_set_ui(half, 0);
    mpz_setbit(half, static_cast<mp_bitcnt_t>(drop - 1));
    const int over = mpz_cmpabs(r, half);
    if (over > 0 || (over == 0 && mpz_tstbit(h, static_cast<mp_bitcnt_t>(drop)) != 0))
    {
      mpz_set_ui(half, 0);
      mpz_setbit(half, static_cast<mp_bitcnt_t>(drop));
      if (mpz_sgn(v) < 0)
        mpz_neg(half, half);
      mpz_add(h, h, half);
      mpz_sub(r, v, h);
    }
  }
  // Each part is a double where its significant bits fit 53 and its exponents the doubles' range.
  bool ok = true;
  auto toDouble = [&ok, unit](const mpz_t z) {
    if (mpz_sgn(z) == 0)
      return 0.0;
    const long low = static_cast<long>(mpz_scan1(z, 0)) + unit;
    const long top = static_cast<long>(mpz_sizeinbase(z, 2)) + unit;
    if (top - low > 53 || low < -1074 || top > 1024)
    {
      ok = false;
      return 0.0;
    }
    long e = 0;
    const double m = mpz_get_d_2exp(&e, z); // exact: at most 53 bits
    return std::ldexp(m, static_cast<int>(e + unit));
  };
  rounded = toDouble(h);
  residual = toDouble(r);
  mpz_clears(mx, mp, v, h, r, half, nullptr);
  return ok;
}

} // namespace fd3
