// Double-double numbers (Dekker 1971; error bounds after Joldes, Muller, Popescu 2017): a value
// hi + lo with |lo| <= u |hi| (u = 2^-53), about 106 significant bits. The predicates use them as
// a stage between the float filters and exact expansions: a determinant of exact coordinate
// differences evaluated in double-double, whose error is bounded by a small multiple of u^2 times
// the determinant's permanent, settles almost every case that the float filters leave open, at a
// tenth of the cost of the exact evaluation.
//
// Error of each operation, as an absolute error relative to the "permanent" of its inputs (|x||y|
// for a product, |x| + |y| for a sum), the measure in which errors add up along a sum of products:
//   mul: x.hi*y.hi exact (twoProduct); x.hi*y.lo and x.lo*y.hi rounded, x.lo*y.lo dropped (each
//        <= u^2 |x||y|); their sum and the fold into the low part rounded: <= 8 u^2 |x||y|.
//   add: the high parts added exactly (twoSum), the low parts rounded twice: <= 3 u^2 (|x| + |y|).
// Both renormalize with an exact twoSum, so the result is again a double-double.
#ifndef fd3_DoubleDouble_h
#define fd3_DoubleDouble_h

#include "exact/Expansion.h"

namespace fd3
{

struct DoubleDouble
{
  double hi = 0, lo = 0;

  /// a - b, exactly.
  static DoubleDouble difference(double a, double b)
  {
    DoubleDouble d;
    twoDiff(a, b, d.hi, d.lo);
    return d;
  }
  double value() const { return hi + lo; }
};

inline DoubleDouble operator+(DoubleDouble x, DoubleDouble y)
{
  double sh, sl;
  twoSum(x.hi, y.hi, sh, sl);
  sl += x.lo + y.lo;
  DoubleDouble z;
  twoSum(sh, sl, z.hi, z.lo);
  return z;
}

inline DoubleDouble operator-(DoubleDouble x)
{
  return {-x.hi, -x.lo};
}

inline DoubleDouble operator-(DoubleDouble x, DoubleDouble y)
{
  return x + -y;
}

inline DoubleDouble operator*(DoubleDouble x, DoubleDouble y)
{
  double ph, pl;
  twoProduct(x.hi, y.hi, ph, pl);
  pl += x.hi * y.lo + x.lo * y.hi;
  DoubleDouble z;
  twoSum(ph, pl, z.hi, z.lo);
  return z;
}

} // namespace fd3

#endif
