// Helpers shared by the periodic Core tests: the validator's view of a periodic run, and its
// tetrahedra compared up to a translation.
#ifndef fd3_PeriodicTestUtilities_h
#define fd3_PeriodicTestUtilities_h

#include "PeriodicValidator.h"
#include "fd3/Periodic.h"

#include <algorithm>
#include <array>
#include <set>
#include <vector>

namespace fd3test
{
inline PeriodicDomain domainOf(const fd3::PeriodicBox& box)
{
  PeriodicDomain domain;
  for (int k = 0; k < 3; ++k)
  {
    domain.lo[k] = box.lo[k];
    domain.hi[k] = box.hi[k];
    domain.periodic[k] = box.periodic[k];
  }
  return domain;
}

inline std::vector<PeriodicTetrahedron> tetrahedraOf(const fd3::PeriodicTriangulation& t)
{
  std::vector<PeriodicTetrahedron> out(t.numberOfTetrahedra());
  for (std::size_t c = 0; c < out.size(); ++c)
    for (int i = 0; i < 4; ++i)
    {
      out[c].ids[i] = t.tetrahedra[4 * c + i];
      for (int k = 0; k < 3; ++k)
        out[c].offsets[i][k] = t.offsets[12 * c + 3 * i + k];
    }
  return out;
}

/// The tetrahedra as sets of (id, offset) up to a translation, for comparing two runs.
inline std::set<std::array<std::array<int, 4>, 4>> canonical(const fd3::PeriodicTriangulation& t)
{
  std::set<std::array<std::array<int, 4>, 4>> out;
  for (std::size_t c = 0; c < t.numberOfTetrahedra(); ++c)
  {
    std::array<std::array<int, 4>, 4> v;
    for (int i = 0; i < 4; ++i)
      v[i] = {int(t.tetrahedra[4 * c + i]), t.offsets[12 * c + 3 * i],
        t.offsets[12 * c + 3 * i + 1], t.offsets[12 * c + 3 * i + 2]};
    std::sort(v.begin(), v.end());
    out.insert(v);
  }
  return out;
}

inline double sum(const fd3::VoronoiCells::Doubles& values)
{
  double total = 0;
  for (const double v : values)
    total += v;
  return total;
}
} // namespace fd3test

#endif
