#include "exact/Expansion.h"

#include <algorithm>

namespace fd3
{

void ExpansionArena::grow(std::size_t needed)
{
  const std::size_t capacity = std::max({2 * buffer_.size(), 2 * needed, std::size_t(4096)});
  if (!buffer_.empty())
    retired_.push_back(std::move(buffer_));
  buffer_ = std::vector<double>(capacity);
  top_ = 0;
}

// Merge e and f by magnitude and accumulate with error-free additions, dropping zero components.
// The output is strongly non-overlapping when the inputs are (round-to-nearest-even arithmetic).
int ExpansionArena::sumZeroElim(Expansion e, Expansion f, double* h)
{
  int ie = 0, jf = 0, out = 0;
  auto smallerFromE = [&]() {
    if (ie >= e.n)
      return false;
    if (jf >= f.n)
      return true;
    return std::fabs(e.c[ie]) < std::fabs(f.c[jf]);
  };
  double q = smallerFromE() ? e.c[ie++] : f.c[jf++];
  bool first = true;
  while (ie < e.n || jf < f.n)
  {
    const double next = smallerFromE() ? e.c[ie++] : f.c[jf++];
    double sum, err;
    if (first)
    {
      // q is the smallest component overall, so |next| >= |q|.
      fastTwoSum(next, q, sum, err);
      first = false;
    }
    else
    {
      twoSum(q, next, sum, err);
    }
    q = sum;
    if (err != 0.0)
      h[out++] = err;
  }
  if (q != 0.0 || out == 0)
    h[out++] = q;
  return out;
}

int ExpansionArena::scaleZeroElim(Expansion e, double b, double* h)
{
  int out = 0;
  double q, err;
  twoProduct(e.c[0], b, q, err);
  if (err != 0.0)
    h[out++] = err;
  for (int i = 1; i < e.n; ++i)
  {
    double productHi, productLo, sum;
    twoProduct(e.c[i], b, productHi, productLo);
    twoSum(q, productLo, sum, err);
    if (err != 0.0)
      h[out++] = err;
    fastTwoSum(productHi, sum, q, err);
    if (err != 0.0)
      h[out++] = err;
  }
  if (q != 0.0 || out == 0)
    h[out++] = q;
  return out;
}

} // namespace fd3
