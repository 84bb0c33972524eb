// Geometric predicates of the kernel, each in two layers: a floating-point evaluation with a
// rigorous error bound (decides almost every call), then exact expansion arithmetic.
// Signs follow VTK's tetrahedron convention:
//   orient3d(a,b,c,d) > 0  iff  (b-a) x (c-a) . (d-a) > 0,
//   inSphere(a,b,c,d,e) > 0 iff e lies strictly inside the circumsphere of the positive tet abcd.
// Coordinates must be scaled so that no product of five of them overflows or underflows
// (Triangulator normalizes its copy of the points to [-1,1]).
#ifndef fd3_Predicates_h
#define fd3_Predicates_h

#include "Expansion.h"

#include <cstddef>
#include <cstdint>

namespace fd3
{

class Predicates
{
public:
  int orient3d(const double* a, const double* b, const double* c, const double* d);
  int inSphere(const double* a, const double* b, const double* c, const double* d, const double* e);
  /// Exactly: is c on the line through a and b (or a == b)?
  bool collinear(const double* a, const double* b, const double* c);

  /// inSphere with ties broken by symbolic perturbation: the lifted coordinate |p|^2 of every point
  /// is lowered by an infinitesimal that is larger for a smaller vertex id. Never returns 0 for a
  /// non-degenerate tetrahedron. `xyz` holds the points by vertex id; `tet` is positively oriented.
  /// Smaller ids (inserted earlier) dominate, which on cospherical input pulls every tetrahedron
  /// towards the first vertex: a fan of about 2 tetrahedra per point instead of a dense tangle.
  int inSphereSoS(const double* xyz, const std::uint32_t tet[4], std::uint32_t e);

  /// Largest span, in bits, of a point set's integer grid for which the exact stage runs in
  /// __int128 arithmetic.
  static constexpr int kIntegerGridBits = 21;
  /// The power of two u such that every coordinate is an integer multiple of u below
  /// 2^kIntegerGridBits * u in magnitude (lattices, integer data), or 0 when there is none.
  static double integerGridUnit(const double* xyz, std::size_t count);
  /// Promises that every point passed from now on lies on that grid (unit > 0), which lets the
  /// exact stage use integer arithmetic instead of expansions.
  void setIntegerGrid(double unit) { inverseGridUnit_ = unit > 0 ? 1.0 / unit : 0.0; }

  std::size_t exactOrientCalls = 0;
  std::size_t exactInSphereCalls = 0;
  std::size_t symbolicTies = 0;
  /// Exact evaluations where a non-zero coordinate difference was below kSmallestSafeDifference:
  /// products of five such differences may underflow, and exactness is no longer guaranteed.
  std::size_t underflowRisks = 0;
  static constexpr double kSmallestSafeDifference = 0x1p-190; // (2^-190)^5 > 2^-969: no underflow

private:
  template <int N>
  void gridDifferences(const double* const x[N], const double* y, std::int64_t out[N][3]) const;
  int orient3dExact(const double* a, const double* b, const double* c, const double* d);
  int inSphereExact(const double* a, const double* b, const double* c, const double* d, const double* e);
  Expansion minor3(Expansion const u[3], Expansion const v[3], Expansion const w[3]);
  void checkUnderflow(const double* const rows[], int count, const double* origin);

  ExpansionArena arena_;
  double inverseGridUnit_ = 0.0;
};

} // namespace fd3

#endif
