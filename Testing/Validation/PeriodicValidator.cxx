#include "PeriodicValidator.h"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

namespace fd3test
{
namespace
{
using Rational = mpq_class;
using Position = std::array<Rational, 3>;
using Offset = std::array<std::int32_t, 3>;
/// (id, offset) of one vertex, comparable: the order that makes keys of faces and tetrahedra.
using Image = std::array<std::int64_t, 4>;

// The face of a tetrahedron opposite vertex i, ordered so that its normal points away from i.
constexpr int kOutward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

Image imageOf(std::uint32_t id, const Offset& offset)
{
  return {id, offset[0], offset[1], offset[2]};
}

Offset minus(const Offset& a, const Offset& b)
{
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

Offset plus(const Offset& a, const Offset& b)
{
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

Rational det3(const Position& u, const Position& v, const Position& w)
{
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
}

Position difference(const Position& a, const Position& b)
{
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

/// (b - a) x (c - a) . (d - a)
Rational orientation(const Position& a, const Position& b, const Position& c, const Position& d)
{
  return det3(difference(b, a), difference(c, a), difference(d, a));
}

/// > 0 iff e is strictly inside the circumsphere of the positive tetrahedron abcd. Weighted
/// (`weights` of abcd, then of e), iff e has a negative power distance to its orthogonal sphere:
/// each lift lowered by its point's weight less e's.
int inSphere(const Position* abcd, const Position& e, const double* weights = nullptr)
{
  Rational rows[4][4];
  for (int i = 0; i < 4; ++i)
  {
    for (int k = 0; k < 3; ++k)
      rows[i][k] = abcd[i][k] - e[k];
    rows[i][3] = rows[i][0] * rows[i][0] + rows[i][1] * rows[i][1] + rows[i][2] * rows[i][2];
    if (weights)
      rows[i][3] -= Rational(weights[i]) - Rational(weights[4]);
  }
  Rational det = 0;
  for (int i = 0; i < 4; ++i)
  {
    Position m[3];
    for (int j = 0, r = 0; j < 4; ++j)
      if (j != i)
        m[r++] = {rows[j][0], rows[j][1], rows[j][2]};
    const Rational minor = det3(m[0], m[1], m[2]);
    det += (i % 2 == 0 ? -1 : 1) * rows[i][3] * minor;
  }
  // det[(x - e, |x - e|^2)] is negative for e inside a positive tetrahedron.
  return -sgn(det);
}

/// A set of vertices up to translation: the sorted images, translated so that one image of the
/// lowest id has offset 0, the lexicographically least such choice. `translation` is what was
/// added to the offsets, `odd` the parity of the sort.
template <std::size_t N>
struct Normalized
{
  std::array<Image, N> key;
  Offset translation;
  bool odd = false;
};

template <std::size_t N>
Normalized<N> normalize(
  const std::array<std::uint32_t, N>& ids, const std::array<Offset, N>& offsets)
{
  const std::uint32_t lowest = *std::min_element(ids.begin(), ids.end());
  Normalized<N> best;
  bool found = false;
  for (std::size_t anchor = 0; anchor < N; ++anchor)
  {
    if (ids[anchor] != lowest)
      continue;
    Normalized<N> candidate;
    candidate.translation = minus(Offset{0, 0, 0}, offsets[anchor]);
    for (std::size_t i = 0; i < N; ++i)
      candidate.key[i] = imageOf(ids[i], minus(offsets[i], offsets[anchor]));
    // Insertion sort, counting transpositions for the parity.
    for (std::size_t i = 1; i < N; ++i)
      for (std::size_t j = i; j > 0 && candidate.key[j] < candidate.key[j - 1]; --j)
      {
        std::swap(candidate.key[j], candidate.key[j - 1]);
        candidate.odd = !candidate.odd;
      }
    if (!found || candidate.key < best.key)
      best = candidate;
    found = true;
  }
  return best;
}

struct FaceUse
{
  std::size_t tet;
  int opposite;
  Offset translation;
  bool odd;
};

class PeriodicChecker
{
public:
  PeriodicChecker(const double* xyz, std::size_t count, const PeriodicDomain& domain,
    const std::vector<PeriodicTetrahedron>& tets, const ValidityOptions& options,
    ValidityReport& report)
    : xyz_(xyz), count_(count), domain_(domain), tets_(tets),
      requireDelaunay_(options.requireDelaunay), weights_(options.weights), hidden_(count, false),
      report_(report)
  {
    for (const std::uint32_t h : options.hidden)
      if (h < count)
        hidden_[h] = true;
      else
        fail("hidden point " + std::to_string(h) + " is out of range");
  }

  void run()
  {
    report_.tetrahedra = tets_.size();
    if (!checkDomain())
      return;
    wrapPoints();
    if (!checkIdsOffsetsAndOrientation())
      return;
    checkEachOnce();
    checkFaces();
    checkVolume();
    checkVertices();
    checkHidden();
  }

private:
  void fail(const std::string& message)
  {
    if (report_.errors.size() < 100)
      report_.errors.push_back(message);
  }

  bool checkDomain()
  {
    periodicAxes_ = 0;
    for (int k = 0; k < 3; ++k)
    {
      if (!(domain_.lo[k] < domain_.hi[k]) || !std::isfinite(domain_.hi[k] - domain_.lo[k]))
      {
        fail("the box is empty or not finite on axis " + std::to_string(k));
        return false;
      }
      period_[k] = Rational(domain_.hi[k]) - Rational(domain_.lo[k]);
      periodicAxes_ += domain_.periodic[k];
    }
    if (periodicAxes_ == 0)
      fail("no axis is periodic: checkTriangulation() checks such a tetrahedralization");
    finite_.resize(count_);
    for (std::size_t i = 0; i < count_; ++i)
      finite_[i] = std::isfinite(xyz_[3 * i]) && std::isfinite(xyz_[3 * i + 1]) &&
        std::isfinite(xyz_[3 * i + 2]) && (!weights_ || std::isfinite(weights_[i]));
    return periodicAxes_ > 0;
  }

  /// Each point moved by whole periods into [lo, hi) along the periodic axes, exactly.
  void wrapPoints()
  {
    wrapped_.resize(count_);
    for (std::size_t i = 0; i < count_; ++i)
      for (int k = 0; k < 3 && finite_[i]; ++k)
      {
        Rational x(xyz_[3 * i + k]);
        if (domain_.periodic[k])
        {
          const Rational periods = (x - Rational(domain_.lo[k])) / period_[k];
          mpz_class whole;
          mpz_fdiv_q(whole.get_mpz_t(), periods.get_num_mpz_t(), periods.get_den_mpz_t());
          x -= Rational(whole) * period_[k];
        }
        wrapped_[i][k] = x;
      }
  }

  Position position(std::uint32_t id, const Offset& offset) const
  {
    Position p = wrapped_[id];
    for (int k = 0; k < 3; ++k)
      p[k] += offset[k] * period_[k];
    return p;
  }

  /// The positions of tetrahedron t's vertices.
  std::array<Position, 4> positions(std::size_t t) const
  {
    std::array<Position, 4> p;
    for (int i = 0; i < 4; ++i)
      p[i] = position(tets_[t].ids[i], tets_[t].offsets[i]);
    return p;
  }

  bool checkIdsOffsetsAndOrientation()
  {
    bool idsValid = true;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      for (int i = 0; i < 4; ++i)
      {
        if (tets_[t].ids[i] >= count_ || !finite_[tets_[t].ids[i]])
        {
          fail("tetrahedron " + std::to_string(t) + " has an id out of range or of a point " +
            "that is not finite");
          idsValid = false;
        }
        for (int k = 0; k < 3; ++k)
          if (!domain_.periodic[k] && tets_[t].offsets[i][k] != 0)
            fail("tetrahedron " + std::to_string(t) + " has an offset on an axis that is not " +
              "periodic");
      }
    if (!idsValid)
      return false;
    for (std::size_t t = 0; t < tets_.size(); ++t)
    {
      const auto p = positions(t);
      const Rational six = orientation(p[0], p[1], p[2], p[3]);
      if (sgn(six) <= 0)
        fail("tetrahedron " + std::to_string(t) + (sgn(six) == 0 ? " is flat" : " is inverted"));
      sixVolume_ += six;
    }
    return true;
  }

  void checkEachOnce()
  {
    std::set<std::array<Image, 4>> seen;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      if (!seen.insert(normalize<4>(tets_[t].ids, tets_[t].offsets).key).second)
        fail("tetrahedron " + std::to_string(t) + " repeats another (up to a translation)");
  }

  void checkFaces()
  {
    std::map<std::array<Image, 3>, std::vector<FaceUse>> faces;
    for (std::size_t t = 0; t < tets_.size(); ++t)
      for (int f = 0; f < 4; ++f)
      {
        std::array<std::uint32_t, 3> ids;
        std::array<Offset, 3> offsets;
        for (int i = 0; i < 3; ++i)
        {
          ids[i] = tets_[t].ids[kOutward[f][i]];
          offsets[i] = tets_[t].offsets[kOutward[f][i]];
        }
        const Normalized<3> face = normalize<3>(ids, offsets);
        faces[face.key].push_back({t, f, face.translation, face.odd});
      }
    for (const auto& [key, uses] : faces)
    {
      if (uses.size() > 2)
        fail("a face is shared by " + std::to_string(uses.size()) + " tetrahedra");
      else if (uses.size() == 1)
        checkHullFace(uses[0]);
      else if (uses[0].odd == uses[1].odd)
        fail("two tetrahedra on the same side of a face (tetrahedra " +
          std::to_string(uses[0].tet) + " and " + std::to_string(uses[1].tet) + ")");
      else
      {
        ++report_.interiorFaces;
        if (requireDelaunay_)
        {
          checkLocallyDelaunay(uses[0], uses[1]);
          checkLocallyDelaunay(uses[1], uses[0]);
        }
      }
    }
  }

  /// The fourth point of `other`, in the frame of `use`'s tetrahedron, is not strictly inside its
  /// circumsphere.
  void checkLocallyDelaunay(const FaceUse& use, const FaceUse& other)
  {
    const auto p = positions(use.tet);
    const PeriodicTetrahedron& o = tets_[other.tet];
    // Both faces coincide once translated by their own translations.
    const Offset shift = minus(other.translation, use.translation);
    const Position apex = position(o.ids[other.opposite], plus(o.offsets[other.opposite], shift));
    const std::array<double, 5> w = weightsOf(tets_[use.tet].ids, o.ids[other.opposite]);
    if (inSphere(p.data(), apex, weights_ ? w.data() : nullptr) > 0)
      fail("face between tetrahedra " + std::to_string(use.tet) + " and " +
        std::to_string(other.tet) + " is not locally " + (weights_ ? "regular" : "Delaunay"));
  }

  /// The weights of four vertices, then of a fifth point (zeros where unweighted).
  std::array<double, 5> weightsOf(const std::array<std::uint32_t, 4>& ids, std::uint32_t e) const
  {
    std::array<double, 5> w{};
    for (int i = 0; i < 4 && weights_; ++i)
      w[i] = weights_[ids[i]];
    w[4] = weights_ ? weights_[e] : 0.0;
    return w;
  }

  void checkHullFace(const FaceUse& use)
  {
    ++report_.hullFaces;
    if (periodicAxes_ == 3)
    {
      fail("a face of tetrahedron " + std::to_string(use.tet) + " has no tetrahedron across it");
      return;
    }
    const auto p = positions(use.tet);
    const Position& a = p[kOutward[use.opposite][0]];
    const Position u = difference(p[kOutward[use.opposite][1]], a);
    const Position v = difference(p[kOutward[use.opposite][2]], a);
    const Position normal = {
      u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k)
      if (domain_.periodic[k] && sgn(normal[k]) != 0)
      {
        fail("hull face of tetrahedron " + std::to_string(use.tet) + " is not parallel to the " +
          "periodic axes");
        return;
      }
    // Its plane is invariant under the periods: the wrapped points stand for every image.
    for (std::size_t i = 0; i < count_; ++i)
    {
      if (!finite_[i])
        continue;
      const Position d = difference(wrapped_[i], a);
      if (sgn(normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2]) > 0)
      {
        fail("point " + std::to_string(i) + " lies beyond a hull face");
        return;
      }
    }
  }

  /// One period of the hull of the periodic set: the box where every axis is periodic; the
  /// periods' product times the extent, or the area of the 2D hull, of the points along the axes
  /// that are not.
  void checkVolume()
  {
    Rational periods = 1;
    int free[3], freeCount = 0;
    for (int k = 0; k < 3; ++k)
    {
      if (domain_.periodic[k])
        periods *= period_[k];
      else
        free[freeCount++] = k;
    }
    Rational expected = periods;
    const std::vector<Position> points = finitePlaces();
    if (freeCount == 1 && !points.empty())
    {
      Rational lowest = points[0][free[0]], highest = lowest;
      for (const Position& p : points)
      {
        lowest = std::min(lowest, p[free[0]]);
        highest = std::max(highest, p[free[0]]);
      }
      expected *= highest - lowest;
    }
    else if (freeCount == 2)
      expected *= hullArea(free[0], free[1]);
    if (sixVolume_ != 6 * expected)
      fail("the tetrahedra's volumes sum to " + Rational(sixVolume_ / 6).get_str() +
        ", not to one period of the hull, " + expected.get_str());
  }

  /// The area of the convex hull of the points projected on axes (u, v): Andrew's monotone chain.
  std::vector<Position> finitePlaces() const
  {
    std::vector<Position> out;
    for (std::size_t i = 0; i < count_; ++i)
      if (finite_[i] && !hidden_[i])
        out.push_back(wrapped_[i]);
    return out;
  }

  Rational hullArea(int u, int v) const
  {
    std::vector<std::array<Rational, 2>> q;
    for (const Position& p : finitePlaces())
      q.push_back({p[u], p[v]});
    std::sort(q.begin(), q.end());
    q.erase(std::unique(q.begin(), q.end()), q.end());
    if (q.size() < 3)
      return 0;
    auto cross = [](const std::array<Rational, 2>& o, const std::array<Rational, 2>& a,
                   const std::array<Rational, 2>& b) -> Rational {
      return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    };
    std::vector<std::array<Rational, 2>> hull(2 * q.size());
    std::size_t n = 0;
    for (std::size_t i = 0; i < q.size(); ++i)
    {
      while (n >= 2 && sgn(cross(hull[n - 2], hull[n - 1], q[i])) <= 0)
        --n;
      hull[n++] = q[i];
    }
    for (std::size_t i = q.size() - 1, lower = n + 1; i-- > 0;)
    {
      while (n >= lower && sgn(cross(hull[n - 2], hull[n - 1], q[i])) <= 0)
        --n;
      hull[n++] = q[i];
    }
    Rational twice = 0;
    for (std::size_t i = 0; i + 1 < n; ++i)
      twice += hull[i][0] * hull[i + 1][1] - hull[i + 1][0] * hull[i][1];
    return twice / 2;
  }

  /// Every distinct point a vertex, by exactly one of the ids at its position.
  void checkVertices()
  {
    std::vector<bool> used(count_, false);
    for (const PeriodicTetrahedron& t : tets_)
      for (std::uint32_t id : t.ids)
        used[id] = true;
    std::map<Position, std::vector<std::uint32_t>> at;
    for (std::size_t i = 0; i < count_; ++i)
      if (finite_[i])
        at[wrapped_[i]].push_back(static_cast<std::uint32_t>(i));
    report_.distinctPoints = at.size();
    for (const auto& [position, ids] : at)
    {
      const auto n =
        std::count_if(ids.begin(), ids.end(), [&](std::uint32_t i) { return used[i]; });
      // A position of hidden points: each one there hidden, or a copy of one of its weight.
      std::set<double> hiddenWeights;
      for (const std::uint32_t i : ids)
        if (hidden_[i] && weights_)
          hiddenWeights.insert(weights_[i]);
      const bool allHidden = std::all_of(ids.begin(), ids.end(), [&](std::uint32_t i) {
        return hidden_[i] || (weights_ && hiddenWeights.count(weights_[i]));
      });
      report_.usedVertices += n;
      if (n != (allHidden ? 0 : 1))
        fail("point " + std::to_string(ids[0]) + " is a vertex " + std::to_string(n) +
          " times (by its id or those of its copies)");
      for (const std::uint32_t i : ids)
      {
        if (hidden_[i] && used[i])
          fail("hidden point " + std::to_string(i) + " is a vertex");
        const bool repeat = hidden_[i] && weights_ &&
          std::any_of(ids.begin(), ids.end(),
            [&](std::uint32_t j) { return used[j] && weights_[j] == weights_[i]; });
        if (repeat)
          fail("hidden point " + std::to_string(i) + " repeats a vertex of its weight");
      }
    }
  }

  /// Each hidden point, of non-negative power distance to the orthosphere of a translate of a
  /// tetrahedron that holds it, or lighter than another point at its position.
  void checkHidden()
  {
    if (!weights_)
      return;
    std::map<Position, double> heaviest;
    for (std::size_t i = 0; i < count_; ++i)
      if (finite_[i])
      {
        auto [at, first] = heaviest.try_emplace(wrapped_[i], weights_[i]);
        at->second = std::max(at->second, weights_[i]);
      }
    for (std::uint32_t h = 0; h < count_; ++h)
      if (hidden_[h] && finite_[h] && !(weights_[h] < heaviest[wrapped_[h]]) && !holdsHidden(h))
        fail("point " + std::to_string(h) + " is listed hidden, but no tetrahedron hides it");
  }

  /// Whether some translate of a tetrahedron holds hidden point h without its orthosphere
  /// conflicting with it. Translates are tried where the tetrahedron's box, in doubles and a
  /// little wider, holds the point moved by whole periods.
  bool holdsHidden(std::uint32_t h)
  {
    if (boxes_.empty())
      for (std::size_t t = 0; t < tets_.size(); ++t)
      {
        const auto p = positions(t);
        std::array<double, 6> box;
        for (int k = 0; k < 3; ++k)
        {
          double lo = p[0][k].get_d(), hi = lo;
          for (int i = 1; i < 4; ++i)
          {
            lo = std::min(lo, p[i][k].get_d());
            hi = std::max(hi, p[i][k].get_d());
          }
          const double slack = 1e-9 * (hi - lo + std::fabs(lo) + std::fabs(hi));
          box[k] = lo - slack;
          box[3 + k] = hi + slack;
        }
        boxes_.push_back(box);
      }
    double here[3], period[3];
    for (int k = 0; k < 3; ++k)
    {
      here[k] = wrapped_[h][k].get_d();
      period[k] = period_[k].get_d();
    }
    for (std::size_t t = 0; t < tets_.size(); ++t)
    {
      const double* lo = boxes_[t].data();
      const double* hi = lo + 3;
      std::int32_t first[3], last[3];
      bool near = true;
      for (int k = 0; k < 3; ++k)
      {
        first[k] = last[k] = 0;
        if (domain_.periodic[k])
        {
          first[k] = std::int32_t(std::ceil((lo[k] - here[k]) / period[k]));
          last[k] = std::int32_t(std::floor((hi[k] - here[k]) / period[k]));
        }
        near = near && first[k] <= last[k] && here[k] + first[k] * period[k] <= hi[k] &&
          here[k] + last[k] * period[k] >= lo[k];
      }
      if (!near)
        continue;
      const auto p = positions(t);
      const std::array<double, 5> w = weightsOf(tets_[t].ids, h);
      for (std::int32_t x = first[0]; x <= last[0]; ++x)
        for (std::int32_t y = first[1]; y <= last[1]; ++y)
          for (std::int32_t z = first[2]; z <= last[2]; ++z)
          {
            const Position e = position(h, {x, y, z});
            bool inside = true;
            for (int f = 0; f < 4 && inside; ++f)
            {
              std::array<Position, 4> q = p;
              q[f] = e;
              inside = sgn(orientation(q[0], q[1], q[2], q[3])) >= 0;
            }
            if (inside && inSphere(p.data(), e, w.data()) <= 0)
              return true;
          }
    }
    return false;
  }

  const double* xyz_;
  std::size_t count_;
  const PeriodicDomain& domain_;
  const std::vector<PeriodicTetrahedron>& tets_;
  bool requireDelaunay_;
  const double* weights_;
  std::vector<bool> hidden_;
  ValidityReport& report_;
  Rational period_[3];
  int periodicAxes_ = 0;
  std::vector<bool> finite_; // points that are not finite are left out
  std::vector<Position> wrapped_;
  std::vector<std::array<double, 6>> boxes_; // of the tetrahedra, lo then hi, in doubles
  Rational sixVolume_ = 0;
};
} // namespace

ValidityReport checkPeriodicTriangulation(const double* xyz, std::size_t count,
  const PeriodicDomain& domain, const std::vector<PeriodicTetrahedron>& tets, bool requireDelaunay)
{
  ValidityOptions options;
  options.requireDelaunay = requireDelaunay;
  return checkPeriodicTriangulation(xyz, count, domain, tets, options);
}

ValidityReport checkPeriodicTriangulation(const double* xyz, std::size_t count,
  const PeriodicDomain& domain, const std::vector<PeriodicTetrahedron>& tets,
  const ValidityOptions& options)
{
  ValidityReport report;
  PeriodicChecker(xyz, count, domain, tets, options, report).run();
  return report;
}

} // namespace fd3test
