// Exact floating-point expansion arithmetic (Priest, Shewchuk): a number is a sum of doubles of
// increasing magnitude that do not overlap. Sums and products of doubles are captured without
// error, so the sign of a polynomial in the input coordinates is decided exactly. Written for this
// project from the published algorithms; no external code. Requires IEEE round-to-nearest doubles
// and no contraction into FMA (Core builds with -ffp-contract=off).
#ifndef fd3_Expansion_h
#define fd3_Expansion_h

#include <cmath>
#include <vector>

namespace fd3
{

inline void twoSum(double a, double b, double& sum, double& err)
{
  sum = a + b;
  const double bVirtual = sum - a;
  const double aVirtual = sum - bVirtual;
  err = (a - aVirtual) + (b - bVirtual);
}

inline void twoDiff(double a, double b, double& diff, double& err)
{
  diff = a - b;
  const double bVirtual = a - diff;
  const double aVirtual = diff + bVirtual;
  err = (a - aVirtual) + (bVirtual - b);
}

// Requires |a| >= |b| (or a == 0).
inline void fastTwoSum(double a, double b, double& sum, double& err)
{
  sum = a + b;
  err = b - (sum - a);
}

inline void twoProduct(double a, double b, double& product, double& err)
{
  product = a * b;
#if defined(__FMA__)
  err = std::fma(a, b, -product);
#else
  // Dekker's split into two 26-bit halves.
  constexpr double splitter = 134217729.0; // 2^27 + 1
  double c = splitter * a;
  const double aHi = c - (c - a), aLo = a - aHi;
  c = splitter * b;
  const double bHi = c - (c - b), bLo = b - bHi;
  err = aLo * bLo - (((product - aHi * bHi) - aLo * bHi) - aHi * bLo);
#endif
}

/// A view of an expansion living in an ExpansionArena. Components are ordered by increasing
/// magnitude and zero components are eliminated; zero itself is the single component 0.
struct Expansion
{
  const double* c;
  int n;
  int sign() const { return (c[n - 1] > 0) - (c[n - 1] < 0); }
};

/// Scratch memory for one exact evaluation: a bump allocator that is reset by the caller, so the
/// exact path does no heap allocation once the buffer has grown to the largest predicate.
class ExpansionArena
{
public:
  void reset()
  {
    top_ = 0;
    retired_.clear();
  }

  Expansion fromDifference(double a, double b)
  {
    double* out = take(2);
    twoDiff(a, b, out[1], out[0]);
    return compact(out, 2);
  }

  Expansion add(Expansion e, Expansion f)
  {
    double* h = take(e.n + f.n);
    return {h, sumZeroElim(e, f, h)};
  }

  Expansion negate(Expansion e)
  {
    double* h = take(e.n);
    for (int i = 0; i < e.n; ++i)
      h[i] = -e.c[i];
    return {h, e.n};
  }

  Expansion subtract(Expansion e, Expansion f) { return add(e, negate(f)); }

  Expansion scale(Expansion e, double b)
  {
    double* h = take(2 * e.n);
    return {h, scaleZeroElim(e, b, h)};
  }

  Expansion multiply(Expansion e, Expansion f)
  {
    if (e.n < f.n)
      std::swap(e, f);
    Expansion acc = scale(e, f.c[0]);
    for (int i = 1; i < f.n; ++i)
      acc = add(acc, scale(e, f.c[i]));
    return acc;
  }

private:
  double* take(int n)
  {
    if (top_ + static_cast<std::size_t>(n) > buffer_.size())
      grow(static_cast<std::size_t>(n));
    double* p = buffer_.data() + top_;
    top_ += static_cast<std::size_t>(n);
    return p;
  }

  // Earlier views must stay valid, so a full buffer is retired (kept alive until reset), not moved.
  void grow(std::size_t needed);

  static Expansion compact(double* c, int n)
  {
    if (c[0] == 0.0 && n == 2)
      return {c + 1, 1};
    return {c, n};
  }

  static int sumZeroElim(Expansion e, Expansion f, double* h);
  static int scaleZeroElim(Expansion e, double b, double* h);

  std::vector<double> buffer_;
  std::vector<std::vector<double>> retired_;
  std::size_t top_ = 0;
};

} // namespace fd3

#endif
