#include "ExactValidator.h"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

namespace fd3test
{
namespace
{
// Double-precision results are trusted only beyond this fraction of the permanent, a margin
// thousands of times wider than the true rounding error of these formulas.
constexpr double kMargin = 1e-11;

int sign(const mpq_class& x)
{
  return sgn(x);
}

template <typename T>
T det3(const T u[3], const T v[3], const T w[3])
{
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
}

template <typename T>
T perm3(const T u[3], const T v[3], const T w[3])
{
  using std::fabs;
  return fabs(u[0]) * (fabs(v[1] * w[2]) + fabs(v[2] * w[1])) +
    fabs(u[1]) * (fabs(v[0] * w[2]) + fabs(v[2] * w[0])) +
    fabs(u[2]) * (fabs(v[0] * w[1]) + fabs(v[1] * w[0]));
}

/// Whether every difference is 0 or within [2^-100, 2^100]: then no product of five leaves the
/// normal range, and no rounding error is lost to underflow or overflow.
bool inRange(const double* differences, int count)
{
  for (int i = 0; i < count; ++i)
  {
    const double x = std::fabs(differences[i]);
    if (x != 0 && !(x >= 0x1p-100 && x <= 0x1p100))
      return false;
  }
  return true;
}

bool trusted(double value, double permanent)
{
  return std::isfinite(value) && std::isfinite(permanent) && permanent > 1e-200 &&
    std::fabs(value) > kMargin * permanent;
}
} // namespace

int exactOrient3d(const double* a, const double* b, const double* c, const double* d)
{
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  const double value = det3(u, v, w);
  if (inRange(u, 3) && inRange(v, 3) && inRange(w, 3) && trusted(value, perm3(u, v, w)))
    return value > 0 ? 1 : -1;
  mpq_class U[3], V[3], W[3];
  for (int k = 0; k < 3; ++k)
  {
    U[k] = mpq_class(b[k]) - mpq_class(a[k]);
    V[k] = mpq_class(c[k]) - mpq_class(a[k]);
    W[k] = mpq_class(d[k]) - mpq_class(a[k]);
  }
  return sign(det3(U, V, W));
}

int exactInSphere(
  const double* a, const double* b, const double* c, const double* d, const double* e)
{
  // Rows (x - e, |x - e|^2); the 4x4 determinant is negative for e inside a positive tetrahedron.
  const double* rows[4] = {a, b, c, d};
  double r[4][4];
  for (int i = 0; i < 4; ++i)
  {
    for (int k = 0; k < 3; ++k)
      r[i][k] = rows[i][k] - e[k];
    r[i][3] = r[i][0] * r[i][0] + r[i][1] * r[i][1] + r[i][2] * r[i][2];
  }
  double value = 0, permanent = 0;
  bool differencesInRange = true;
  for (int i = 0; i < 4; ++i)
    differencesInRange = differencesInRange && inRange(r[i], 3);
  for (int i = 0; i < 4; ++i)
  {
    const double* m[3];
    int k = 0;
    for (int j = 0; j < 4; ++j)
      if (j != i)
        m[k++] = r[j];
    const double s = (i % 2 == 0) ? -1.0 : 1.0;
    value += s * r[i][3] * det3(m[0], m[1], m[2]);
    permanent += r[i][3] * perm3(m[0], m[1], m[2]);
  }
  if (differencesInRange && trusted(value, permanent))
    return value < 0 ? 1 : -1;
  const double zero[4] = {0, 0, 0, 0};
  return exactPowerTest(rows, e, zero, 0);
}

int exactPowerTest(const double* const p[4], const double* e, const double w[4], double we)
{
  // Rows (x - e, |x - e|^2 - (w - we)), rational, no filter: exactInSphere()'s exact stage.
  mpq_class R[4][4];
  for (int i = 0; i < 4; ++i)
  {
    for (int k = 0; k < 3; ++k)
      R[i][k] = mpq_class(p[i][k]) - mpq_class(e[k]);
    R[i][3] =
      R[i][0] * R[i][0] + R[i][1] * R[i][1] + R[i][2] * R[i][2] - mpq_class(w[i]) + mpq_class(we);
  }
  mpq_class det = 0;
  for (int i = 0; i < 4; ++i)
  {
    const mpq_class* m[3];
    int k = 0;
    for (int j = 0; j < 4; ++j)
      if (j != i)
        m[k++] = R[j];
    const mpq_class minor = det3(m[0], m[1], m[2]);
    if (i % 2 == 0)
      det -= R[i][3] * minor;
    else
      det += R[i][3] * minor;
  }
  return -sign(det);
}

std::string ValidityReport::summary() const
{
  std::ostringstream s;
  s << tetrahedra << " tetrahedra, " << hullFaces << " hull faces, " << interiorFaces
    << " interior faces, " << usedVertices << " of " << distinctPoints << " distinct points used";
  for (std::size_t i = 0; i < errors.size() && i < 10; ++i)
    s << "\n  " << errors[i];
  if (errors.size() > 10)
    s << "\n  ... " << errors.size() - 10 << " more errors";
  return s.str();
}

namespace
{
struct Face
{
  std::array<std::uint32_t, 3> key; // sorted vertex ids
  std::uint32_t tet;
  int opposite; // local index of the vertex opposite the face
  bool operator<(const Face& o) const { return key < o.key; }
};

// The face of tet t opposite local vertex i, ordered so that its normal points away from vertex i.
std::array<std::uint32_t, 3> outwardFace(const std::uint32_t* t, int i)
{
  static constexpr int kOutward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  return {t[kOutward[i][0]], t[kOutward[i][1]], t[kOutward[i][2]]};
}

class Checker
{
public:
  Checker(const double* xyz, std::size_t count, const std::uint32_t* tets, std::size_t tetCount,
    const ValidityOptions& options, ValidityReport& report)
    : xyz_(xyz), count_(count), tets_(tets), tetCount_(tetCount), options_(options), report_(report)
  {}

  void run()
  {
    report_.tetrahedra = tetCount_;
    if (!checkIdsAndOrientation())
      return;
    checkFaces();
    checkVertices();
    checkSingleCover();
  }

private:
  const double* p(std::uint32_t id) const { return xyz_ + 3 * std::size_t(id); }
  const std::uint32_t* tet(std::size_t t) const { return tets_ + 4 * t; }
  void fail(const std::string& message) { report_.errors.push_back(message); }

  bool checkIdsAndOrientation()
  {
    for (std::size_t t = 0; t < report_.tetrahedra; ++t)
    {
      const std::uint32_t* v = tet(t);
      for (int i = 0; i < 4; ++i)
        if (v[i] >= count_)
        {
          fail("tet " + std::to_string(t) + " has an out-of-range point id");
          return false;
        }
      if (exactOrient3d(p(v[0]), p(v[1]), p(v[2]), p(v[3])) <= 0)
        fail("tet " + std::to_string(t) + " is not positively oriented");
    }
    return report_.errors.empty();
  }

  void checkFaces()
  {
    std::vector<Face> faces;
    faces.reserve(4 * tetCount_);
    for (std::size_t t = 0; t < report_.tetrahedra; ++t)
      for (int i = 0; i < 4; ++i)
      {
        auto key = outwardFace(tet(t), i);
        std::sort(key.begin(), key.end());
        faces.push_back({key, static_cast<std::uint32_t>(t), i});
      }
    std::sort(faces.begin(), faces.end());
    std::vector<std::array<std::uint32_t, 3>> hull;
    for (std::size_t i = 0; i < faces.size();)
    {
      std::size_t j = i;
      while (j < faces.size() && faces[j].key == faces[i].key)
        ++j;
      if (j - i > 2)
        fail("a face is shared by " + std::to_string(j - i) + " tetrahedra");
      else if (j - i == 1)
        hull.push_back(outwardFace(tet(faces[i].tet), faces[i].opposite));
      else
        checkInteriorFace(faces[i], faces[i + 1]);
      i = j;
    }
    report_.hullFaces = hull.size();
    checkHull(hull);
  }

  void checkInteriorFace(const Face& a, const Face& b)
  {
    ++report_.interiorFaces;
    const auto f = outwardFace(tet(a.tet), a.opposite);
    const std::uint32_t beyond = tet(b.tet)[b.opposite];
    if (exactOrient3d(p(f[0]), p(f[1]), p(f[2]), p(beyond)) <= 0)
      fail("two tetrahedra on the same side of their shared face");
    if (!options_.requireDelaunay)
      return;
    const std::uint32_t* v = tet(a.tet);
    if (options_.weights)
    {
      if (powerTest(v, beyond) > 0)
        fail("interior face of tet " + std::to_string(a.tet) + " is not locally regular");
    }
    else if (exactInSphere(p(v[0]), p(v[1]), p(v[2]), p(v[3]), p(beyond)) > 0)
      fail("interior face of tet " + std::to_string(a.tet) + " is not locally Delaunay");
  }

  int powerTest(const std::uint32_t* v, std::uint32_t e) const
  {
    const double* q[4] = {p(v[0]), p(v[1]), p(v[2]), p(v[3])};
    const double* w = options_.weights;
    const double weights[4] = {w[v[0]], w[v[1]], w[v[2]], w[v[3]]};
    return exactPowerTest(q, p(e), weights, w[e]);
  }

  // The boundary must be a closed, connected 2-manifold of genus 0 whose every edge is convex:
  // such a surface bounds a convex body, and with every point a vertex, that body is the hull.
  void checkHull(const std::vector<std::array<std::uint32_t, 3>>& hull)
  {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> directedEdges;
    for (std::size_t f = 0; f < hull.size(); ++f)
      for (int k = 0; k < 3; ++k)
        if (!directedEdges.emplace(std::make_pair(hull[f][k], hull[f][(k + 1) % 3]), f).second)
          fail("hull edge used twice in the same direction");
    std::vector<std::size_t> component(hull.size());
    std::iota(component.begin(), component.end(), 0);
    auto root = [&](std::size_t x) {
      while (component[x] != x)
        x = component[x] = component[component[x]];
      return x;
    };
    std::set<std::uint32_t> hullVertices;
    for (const auto& [edge, f] : directedEdges)
    {
      hullVertices.insert(edge.first);
      const auto twin = directedEdges.find({edge.second, edge.first});
      if (twin == directedEdges.end())
      {
        fail("hull is not closed");
        continue;
      }
      component[root(f)] = root(twin->second);
      const auto& g = hull[twin->second];
      const std::uint32_t apex = g[0] != edge.first && g[0] != edge.second
        ? g[0]
        : (g[1] != edge.first && g[1] != edge.second ? g[1] : g[2]);
      const auto& h = hull[f];
      if (exactOrient3d(p(h[0]), p(h[1]), p(h[2]), p(apex)) > 0)
        fail("hull is not convex at an edge");
    }
    std::size_t roots = 0;
    for (std::size_t f = 0; f < hull.size(); ++f)
      roots += root(f) == f;
    if (roots != 1)
      fail("hull has " + std::to_string(roots) + " components");
    const long euler =
      long(hullVertices.size()) - long(directedEdges.size() / 2) + long(hull.size());
    if (euler != 2)
      fail("hull is not a sphere (Euler characteristic " + std::to_string(euler) + ")");
  }

  bool finite(std::size_t i) const
  {
    return std::isfinite(p(i)[0]) && std::isfinite(p(i)[1]) && std::isfinite(p(i)[2]) &&
      (!options_.weights || std::isfinite(options_.weights[i]));
  }

  void checkVertices()
  {
    using Position = std::array<double, 3>;
    std::map<Position, std::uint32_t> distinct;
    for (std::size_t i = 0; i < count_; ++i)
      if (finite(i))
        distinct.emplace(Position{p(i)[0], p(i)[1], p(i)[2]}, std::uint32_t(i));
    report_.distinctPoints = distinct.size();
    std::set<std::uint32_t> used(tets_, tets_ + 4 * tetCount_);
    report_.usedVertices = used.size();
    std::map<Position, std::uint32_t> usedCoordinates;
    for (std::uint32_t id : used)
      if (!usedCoordinates.emplace(Position{p(id)[0], p(id)[1], p(id)[2]}, id).second)
        fail("two vertices at the same position");
    std::set<Position> hiddenPositions;
    for (const std::uint32_t id : options_.hidden)
    {
      if (id >= count_ || !finite(id) || used.count(id))
      {
        fail("point " + std::to_string(id) + " is listed hidden but is a vertex or not finite");
        continue;
      }
      const Position at{p(id)[0], p(id)[1], p(id)[2]};
      hiddenPositions.insert(at);
      const auto vertex = usedCoordinates.find(at);
      if (vertex != usedCoordinates.end() ? options_.weights[id] > options_.weights[vertex->second]
                                          : !hiddenInTetrahedron(id))
        fail("point " + std::to_string(id) + " is listed hidden but is not");
    }
    std::size_t unused = 0;
    for (const auto& [at, id] : distinct)
      unused += !usedCoordinates.count(at) && !hiddenPositions.count(at);
    if (unused)
      fail(std::to_string(unused) + " distinct points unused");
  }

  /// Whether a tetrahedron contains point h (closed) and h does not conflict with it. Which
  /// tetrahedra may contain it comes from a grid of their bounding boxes, made on first use.
  bool hiddenInTetrahedron(std::uint32_t h)
  {
    if (cells_.empty())
      bucketTetrahedra();
    const std::size_t cell = cellOf(p(h));
    for (const std::uint32_t t : cells_[cell])
    {
      const std::uint32_t* w = tet(t);
      bool inside = true;
      for (int i = 0; i < 4 && inside; ++i)
      {
        const double* q[4] = {p(w[0]), p(w[1]), p(w[2]), p(w[3])};
        q[i] = p(h);
        inside = exactOrient3d(q[0], q[1], q[2], q[3]) >= 0;
      }
      if (inside)
        return powerTest(w, h) <= 0;
    }
    return false; // outside the hull, where no point is hidden
  }

  std::size_t cellOf(const double* x) const
  {
    std::size_t index = 0;
    for (int k = 0; k < 3; ++k)
    {
      const double u = (x[k] - lo_[k]) / (hi_[k] - lo_[k]) * double(side_);
      const std::size_t c = u >= double(side_) ? side_ - 1 : (u > 0 ? std::size_t(u) : 0);
      index = index * side_ + c;
    }
    return index;
  }

  void bucketTetrahedra()
  {
    side_ = std::max<std::size_t>(1, std::size_t(std::cbrt(double(tetCount_) / 8)));
    for (int k = 0; k < 3; ++k)
    {
      lo_[k] = INFINITY;
      hi_[k] = -INFINITY;
    }
    for (std::size_t i = 0; i < 4 * tetCount_; ++i)
      for (int k = 0; k < 3; ++k)
      {
        lo_[k] = std::min(lo_[k], p(tets_[i])[k]);
        hi_[k] = std::max(hi_[k], p(tets_[i])[k]);
      }
    for (int k = 0; k < 3; ++k)
      if (!(hi_[k] > lo_[k]))
        hi_[k] = lo_[k] + 1;
    cells_.assign(side_ * side_ * side_, {});
    for (std::size_t t = 0; t < tetCount_; ++t)
    {
      std::size_t from[3], to[3];
      for (int k = 0; k < 3; ++k)
      {
        double a = INFINITY, b = -INFINITY;
        for (int i = 0; i < 4; ++i)
        {
          a = std::min(a, p(tet(t)[i])[k]);
          b = std::max(b, p(tet(t)[i])[k]);
        }
        double lowCorner[3] = {lo_[0], lo_[1], lo_[2]}, highCorner[3] = {lo_[0], lo_[1], lo_[2]};
        lowCorner[k] = a;
        highCorner[k] = b;
        from[k] = cellOf(lowCorner) / stride(k) % side_;
        to[k] = cellOf(highCorner) / stride(k) % side_;
      }
      for (std::size_t x = from[0]; x <= to[0]; ++x)
        for (std::size_t y = from[1]; y <= to[1]; ++y)
          for (std::size_t z = from[2]; z <= to[2]; ++z)
            cells_[(x * side_ + y) * side_ + z].push_back(std::uint32_t(t));
    }
  }

  std::size_t stride(int k) const { return k == 0 ? side_ * side_ : (k == 1 ? side_ : 1); }

  // Local checks cannot see a triangulation that wraps twice around an edge; counting the
  // tetrahedra that contain an interior point of one of them can.
  void checkSingleCover()
  {
    if (report_.tetrahedra == 0 || !report_.errors.empty())
      return;
    const std::uint32_t* v = tet(0);
    double c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = p(v[0])[k] / 4 + p(v[1])[k] / 4 + p(v[2])[k] / 4 + p(v[3])[k] / 4; // no overflow
    if (exactOrient3d(p(v[0]), p(v[1]), p(v[2]), c) <= 0 ||
      exactOrient3d(p(v[1]), p(v[0]), p(v[3]), c) <= 0 ||
      exactOrient3d(p(v[2]), p(v[3]), p(v[0]), c) <= 0 ||
      exactOrient3d(p(v[3]), p(v[2]), p(v[1]), c) <= 0)
      return; // the rounded centroid is not strictly inside (a tiny sliver): nothing to learn
    std::size_t covering = 0;
    for (std::size_t t = 0; t < report_.tetrahedra; ++t)
    {
      const std::uint32_t* w = tet(t);
      bool inside = true;
      for (int i = 0; i < 4 && inside; ++i)
      {
        const double* q[4] = {p(w[0]), p(w[1]), p(w[2]), p(w[3])};
        q[i] = c;
        inside = exactOrient3d(q[0], q[1], q[2], q[3]) >= 0;
      }
      covering += inside;
    }
    if (covering != 1)
      fail("an interior point is covered by " + std::to_string(covering) + " tetrahedra");
  }

  const double* xyz_;
  std::size_t count_;
  const std::uint32_t* tets_;
  std::size_t tetCount_;
  const ValidityOptions& options_;
  ValidityReport& report_;
  std::vector<std::vector<std::uint32_t>> cells_; // hiddenInTetrahedron()'s grid
  std::size_t side_ = 0;
  double lo_[3], hi_[3];
};
} // namespace

ValidityReport checkTriangulation(const double* xyz, std::size_t count, const std::uint32_t* tets,
  std::size_t tetCount, const ValidityOptions& options)
{
  ValidityReport report;
  Checker(xyz, count, tets, tetCount, options, report).run();
  return report;
}

std::vector<std::array<std::uint32_t, 4>> canonicalTetrahedra(
  const std::uint32_t* tets, std::size_t tetCount)
{
  std::vector<std::array<std::uint32_t, 4>> sorted(tetCount);
  for (std::size_t t = 0; t < tetCount; ++t)
  {
    std::copy(tets + 4 * t, tets + 4 * t + 4, sorted[t].begin());
    std::sort(sorted[t].begin(), sorted[t].end());
  }
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

} // namespace fd3test
