#include "periodic/PeriodicDelaunay.h"

#include "exact/Frame.h"
#include "exact/Predicates.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace fd3
{
namespace
{
// The farthest a point may lie from the box, in periods, and the widest offset of an image.
constexpr double kMostPeriods = 0x1p30;
// Shells widen by half at least, so that the rounds stay few.
constexpr double kWidening = 1.5;
// The first shell, in spacings of evenly spread points: wide enough for nearly every
// tetrahedron of well-spread points, so that one round usually does.
constexpr double kFirstShell = 2.5;
// Relative slack of the certificate's float evaluation: it only needs to be sufficient, and a
// false failure only widens the shell.
constexpr double kSlack = 1e-6;

/// Whether the exact value rounded + residual lies below y.
bool below(double rounded, double residual, double y)
{
  return rounded < y || (rounded == y && residual < 0);
}
} // namespace

PeriodicDelaunay::PeriodicDelaunay(
  const double* xyz, std::size_t count, const PeriodicBox& box, const Options& options)
  : xyz_(xyz), count_(count), box_(box), options_(options)
{
  options_.tolerance = 0;
  options_.volumeThreshold = 0;
  for (int k = 0; k < 3; ++k)
  {
    period_[k] = box.hi[k] - box.lo[k];
    if (!box.periodic[k])
      continue;
    if (!(period_[k] > 0) || !std::isfinite(period_[k]) || !std::isfinite(box.lo[k]))
      throw std::invalid_argument("fd3::triangulatePeriodic: a periodic axis with hi <= lo or "
                                  "not finite");
    ++periodicAxes_;
  }
  if (periodicAxes_ == 0)
    throw std::invalid_argument("fd3::triangulatePeriodic: no periodic axis (use triangulate())");
}

bool PeriodicDelaunay::wrapPoints()
{
  place_.resize(count_);
  placeResidual_.resize(count_);
  wraps_.assign(3 * count_, 0);
  representative_.assign(count_, kNoPoint);
  for (std::size_t i = 0; i < count_; ++i)
  {
    const double* p = xyz_ + 3 * i;
    if (!isFinite(p))
    {
      ++nonFinite_;
      continue;
    }
    representative_[i] = static_cast<std::uint32_t>(i);
    for (int k = 0; k < 3; ++k)
    {
      place_[i][k] = p[k];
      placeResidual_[i][k] = 0;
      if (!box_.periodic[k])
        continue;
      const double periods = std::floor((p[k] - box_.lo[k]) / period_[k]);
      if (!(std::fabs(periods) < kMostPeriods))
        return false;
      // The float quotient may be one off: settle it on the exact places.
      auto wrapped = [&](std::int64_t w, double& rounded, double& residual) {
        return translateExactly(p[k], -w, period_[k], rounded, residual);
      };
      std::int64_t w = static_cast<std::int64_t>(periods);
      double rounded, residual;
      for (int step = 0; step < 4; ++step)
      {
        if (!wrapped(w, rounded, residual))
          return false;
        if (below(rounded, residual, box_.lo[k]))
        {
          --w;
          continue;
        }
        double nextRounded, nextResidual; // one period lower must fall below the box
        if (!wrapped(w + 1, nextRounded, nextResidual))
          return false;
        if (!below(nextRounded, nextResidual, box_.lo[k]))
        {
          ++w;
          continue;
        }
        break;
      }
      place_[i][k] = rounded;
      placeResidual_[i][k] = residual;
      wraps_[3 * i + k] = static_cast<std::int32_t>(w);
    }
  }
  return true;
}

void PeriodicDelaunay::choosePoints()
{
  std::vector<std::uint32_t> order;
  for (std::size_t i = 0; i < count_; ++i)
    if (representative_[i] != kNoPoint)
      order.push_back(static_cast<std::uint32_t>(i));
  // By record, then residual, then id: repeats of an exact place, and places whose records
  // coincide, follow the first of them.
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (place_[a] != place_[b])
      return place_[a] < place_[b];
    if (placeResidual_[a] != placeResidual_[b])
      return placeResidual_[a] < placeResidual_[b];
    return a < b;
  });
  for (std::size_t i = 0; i < order.size();)
  {
    std::size_t end = i + 1;
    while (end < order.size() && place_[order[end]] == place_[order[i]])
      ++end;
    const std::uint32_t first =
      *std::min_element(order.begin() + long(i), order.begin() + long(end));
    for (std::size_t j = i; j < end; ++j)
    {
      const std::uint32_t id = order[j];
      if (id == first)
        continue;
      representative_[id] = first;
      if (placeResidual_[id] == placeResidual_[first])
        ++duplicates_;
      else
        ++close_;
    }
    i = end;
  }
  points_.clear();
  for (std::size_t i = 0; i < count_; ++i)
    if (representative_[i] == i)
      points_.push_back(static_cast<std::uint32_t>(i));
}

void PeriodicDelaunay::chooseFrame()
{
  Bounds extent; // of the places, along every axis
  for (const std::uint32_t id : points_)
    extent.include(place_[id].data());
  double halfDiagonal = 0, freeDiagonal = 0, volume = 1;
  int dimensions = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = box_.periodic[k] ? period_[k] : extent.extent(k);
    if (box_.periodic[k])
      halfDiagonal += 0.25 * e * e;
    else
      freeDiagonal += e * e;
    if (e > 0)
    {
      volume *= e;
      ++dimensions;
    }
  }
  halfDiagonal = std::sqrt(halfDiagonal);
  widest_ = halfDiagonal + std::sqrt(halfDiagonal * halfDiagonal + freeDiagonal);
  spacing_ = std::pow(volume / double(std::max<std::size_t>(points_.size(), 1)), 1.0 / dimensions);
  Bounds frameBox = extent;
  bool shifts[3] = {true, true, true};
  for (int k = 0; k < 3; ++k)
    if (box_.periodic[k])
    {
      // The shell's images, a little beyond it for the rounding of their records.
      const double reach = widest_ * (1 + kSlack) + period_[k];
      frameBox.lo[k] = box_.lo[k] - reach;
      frameBox.hi[k] = box_.lo[k] + period_[k] + reach;
      shifts[k] = false; // images are not among the points checked
    }
  std::vector<double> places;
  for (const std::uint32_t id : points_)
    places.insert(places.end(), place_[id].begin(), place_[id].end());
  checkShifts(places.data(), points_.size(), frameBox, shifts);
  frame_ = frameFor(frameBox, shifts);
  // Every residual must scale exactly too: a multiple of 2^-190 once scaled, as fitsFrame() asks
  // of coordinates (the images' residuals are parts of the places' bits).
  bool fits = fitsFrame(frame_, places.data(), points_.size());
  for (const std::uint32_t id : points_)
    for (const double r : placeResidual_[id])
    {
      const double y = r * frame_.scale;
      fits =
        fits && (std::fabs(y) >= 0x1p-137 || std::ldexp(y, 190) == std::trunc(std::ldexp(y, 190)));
    }
  if (!fits)
    frame_ = identityFrame(frameBox);
}

bool PeriodicDelaunay::addShell(double inner, double outer)
{
  for (const std::uint32_t id : points_)
  {
    // The offsets along each axis that bring the point into [lo - outer, hi + outer].
    std::vector<std::int8_t> along[3];
    for (int k = 0; k < 3; ++k)
    {
      if (!box_.periodic[k])
      {
        along[k] = {0};
        continue;
      }
      const int most = static_cast<int>(std::ceil(outer / period_[k])) + 1;
      for (int j = -most; j <= most; ++j)
      {
        const double x = place_[id][k] + j * period_[k];
        if (x >= box_.lo[k] - outer && x <= box_.hi[k] + outer)
          along[k].push_back(static_cast<std::int8_t>(j));
      }
    }
    auto within = [&](const std::array<std::int8_t, 3>& o, double margin) {
      if (margin < 0)
        return false;
      for (int k = 0; k < 3; ++k)
      {
        const double x = place_[id][k] + o[k] * period_[k];
        if (box_.periodic[k] && !(x >= box_.lo[k] - margin && x <= box_.hi[k] + margin))
          return false;
      }
      return true;
    };
    for (const std::int8_t jx : along[0])
      for (const std::int8_t jy : along[1])
        for (const std::int8_t jz : along[2])
        {
          const std::array<std::int8_t, 3> o = {jx, jy, jz};
          if (within(o, inner))
            continue;
          ImageOf image;
          double at[3];
          for (int k = 0; k < 3; ++k)
          {
            image.source[k] = xyz_[3 * id + k];
            image.offset[k] = o[k] - wraps_[3 * id + k];
            if (!translateExactly(
                  image.source[k], image.offset[k], period_[k], at[k], image.residual[k]))
              return false;
          }
          image.key = perturbationKey(image.source, options_.randomSeed);
          coveringXyz_.insert(coveringXyz_.end(), at, at + 3);
          coveringImages_.push_back(image);
          covering_.push_back({id, o});
        }
  }
  return true;
}

bool PeriodicDelaunay::recordsCollide()
{
  std::vector<std::uint32_t> order(covering_.size());
  std::iota(order.begin(), order.end(), 0u);
  auto record = [&](std::uint32_t c) {
    return std::array<double, 3>{
      coveringXyz_[3 * c], coveringXyz_[3 * c + 1], coveringXyz_[3 * c + 2]};
  };
  std::sort(order.begin(), order.end(),
    [&](std::uint32_t a, std::uint32_t b) { return record(a) < record(b); });
  bool collide = false;
  for (std::size_t i = 1; i < order.size(); ++i)
  {
    const CoveringPoint &a = covering_[order[i - 1]], &b = covering_[order[i]];
    if (record(order[i - 1]) != record(order[i]) || a.owner == b.owner)
      continue;
    // Distinct places (the points were chosen so): the later owner goes.
    const std::uint32_t later = std::max(a.owner, b.owner);
    if (representative_[later] == later)
      ++close_;
    representative_[later] = std::min(a.owner, b.owner);
    collide = true;
  }
  if (collide)
  {
    for (std::uint32_t& id : representative_)
      if (id != kNoPoint)
        while (representative_[id] != id)
          id = representative_[id];
    points_.erase(std::remove_if(points_.begin(), points_.end(),
                    [&](std::uint32_t id) { return representative_[id] != id; }),
      points_.end());
  }
  return collide;
}

double PeriodicDelaunay::neededMargin(const IncrementalDelaunay& mesh) const
{
  // The points' extent along the axes that are not periodic.
  Bounds extent;
  for (const std::uint32_t id : points_)
    extent.include(place_[id].data());
  double needed = margin_;
  mesh.visitTetrahedra([&](const std::uint32_t ids[4], unsigned hull) {
    bool inBox = false;
    for (int i = 0; i < 4; ++i)
    {
      const auto& o = covering_[ids[i]].offset;
      inBox = inBox || (o[0] == 0 && o[1] == 0 && o[2] == 0);
    }
    if (!inBox)
      return;
    if (hull != 0)
    {
      static constexpr int kOutward[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
      for (int f = 0; f < 4; ++f)
      {
        if (!(hull >> f & 1u))
          continue;
        const std::uint32_t face[3] = {
          ids[kOutward[f][0]], ids[kOutward[f][1]], ids[kOutward[f][2]]};
        // A hull face of the covering that a point of the box is on must be one of the repeated
        // set: across the periodic axes, its half-space would take in images.
        const bool atBox = std::any_of(face, face + 3, [&](std::uint32_t c) {
          const auto& o = covering_[c].offset;
          return o[0] == 0 && o[1] == 0 && o[2] == 0;
        });
        if (atBox && (periodicAxes_ == 3 || !parallelToPeriods(face)))
          needed = std::max(needed, kWidening * margin_);
      }
    }
    // The circumsphere, relative to vertex 0, in floats.
    const double* a = &coveringXyz_[3 * ids[0]];
    double u[3][3];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        u[i][k] = coveringXyz_[3 * ids[i + 1] + k] - a[k];
    double lift[3], cross[3][3];
    for (int i = 0; i < 3; ++i)
    {
      lift[i] = u[i][0] * u[i][0] + u[i][1] * u[i][1] + u[i][2] * u[i][2];
      const double* v = u[(i + 1) % 3];
      const double* w = u[(i + 2) % 3];
      cross[i][0] = v[1] * w[2] - v[2] * w[1];
      cross[i][1] = v[2] * w[0] - v[0] * w[2];
      cross[i][2] = v[0] * w[1] - v[1] * w[0];
    }
    const double det = 2 * (u[0][0] * cross[0][0] + u[0][1] * cross[0][1] + u[0][2] * cross[0][2]);
    double c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = (lift[0] * cross[0][k] + lift[1] * cross[1][k] + lift[2] * cross[2][k]) / det;
    const double r = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) * (1 + kSlack);
    if (!std::isfinite(r))
    {
      needed = widest_;
      return;
    }
    // Where the sphere meets the points' extent along the other axes, its reach along the
    // periodic ones.
    double far = 0;
    for (int k = 0; k < 3; ++k)
      if (!box_.periodic[k])
      {
        const double x = a[k] + c[k];
        const double gap = std::max({extent.lo[k] - x, x - extent.hi[k], 0.0});
        far += gap * gap;
      }
    const double reach2 = r * r - far * (1 - kSlack);
    if (reach2 <= 0)
      return;
    const double reach = std::sqrt(reach2) * (1 + kSlack);
    for (int k = 0; k < 3; ++k)
      if (box_.periodic[k])
      {
        const double x = a[k] + c[k];
        const double beyond = std::max(box_.lo[k] - (x - reach), (x + reach) - box_.hi[k]);
        const double slack = kSlack * (std::fabs(x) + reach + period_[k]);
        if (beyond + slack >= margin_)
          needed = std::max(needed, beyond + slack + spacing_);
      }
  });
  return needed;
}

bool PeriodicDelaunay::parallelToPeriods(const std::uint32_t face[3]) const
{
  // The normal's component along axis k vanishes where the face's projection across k is a
  // segment: three collinear points, decided exactly on the images.
  for (int k = 0; k < 3; ++k)
  {
    if (!box_.periodic[k])
      continue;
    double projected[3][3];
    PeriodicImages images;
    for (int i = 0; i < 3; ++i)
    {
      ImageOf image = coveringImages_[face[i]];
      for (int a = 0; a < 3; ++a)
        projected[i][a] = a == k ? 0.0 : coveringXyz_[3 * face[i] + a];
      image.residual[k] = 0;
      images.append(image);
    }
    images.locate(projected[0], 3);
    Predicates predicates;
    predicates.useImages(&images);
    if (!predicates.collinear(projected[0], projected[1], projected[2]))
      return false;
  }
  return true;
}

void PeriodicDelaunay::extract(const Triangulation& covering, PeriodicTriangulation& out) const
{
  const std::size_t n = covering.numberOfTetrahedra();
  for (std::size_t t = 0; t < n; ++t)
  {
    const std::uint32_t* ids = &covering.tetrahedra[4 * t];
    // The copy whose least vertex is in the box.
    std::array<std::int64_t, 4> least = {INT64_MAX, 0, 0, 0};
    for (int i = 0; i < 4; ++i)
    {
      const CoveringPoint& p = covering_[ids[i]];
      least = std::min(least, {p.owner, p.offset[0], p.offset[1], p.offset[2]});
    }
    if (least[1] != 0 || least[2] != 0 || least[3] != 0)
      continue;
    for (int i = 0; i < 4; ++i)
    {
      const CoveringPoint& p = covering_[ids[i]];
      out.tetrahedra.push_back(p.owner);
      out.offsets.insert(out.offsets.end(), p.offset.begin(), p.offset.end());
    }
  }
}

std::unique_ptr<IncrementalDelaunay> PeriodicDelaunay::cover(PeriodicTriangulation& out)
{
  coveringXyz_.clear();
  coveringImages_.clear();
  covering_.clear();
  out.rounds = 0;
  margin_ = std::min(kFirstShell * spacing_, widest_);
  if (!addShell(-1, margin_))
  {
    out.status = Status::OutOfRange;
    return nullptr;
  }
  if (recordsCollide())
    return nullptr;
  auto mesh = IncrementalDelaunay::ofImages(
    coveringXyz_.data(), coveringImages_.data(), covering_.size(), options_, frame_);
  std::size_t inserted = covering_.size();
  while (mesh->status() == Status::Ok && margin_ < widest_)
  {
    const double needed = neededMargin(*mesh);
    if (needed <= margin_)
      break;
    const double wider = std::min(std::max(needed, kWidening * margin_), widest_);
    if (!addShell(margin_, wider))
    {
      out.status = Status::OutOfRange;
      return nullptr;
    }
    margin_ = wider;
    ++out.rounds;
    if (recordsCollide())
      return nullptr;
    mesh->addImages(
      &coveringXyz_[3 * inserted], &coveringImages_[inserted], covering_.size() - inserted);
    inserted = covering_.size();
  }
  return mesh;
}

PeriodicTriangulation PeriodicDelaunay::run()
{
  PeriodicTriangulation out;
  out.stats.inputPoints = count_;
  if (!wrapPoints())
  {
    out.status = Status::OutOfRange;
    return out;
  }
  choosePoints();
  out.stats.nonFinitePoints = nonFinite_;
  if (points_.empty())
  {
    out.status = Status::Empty;
    return out;
  }
  chooseFrame();
  std::unique_ptr<IncrementalDelaunay> mesh;
  while (!mesh && out.status == Status::Ok)
    mesh = cover(out);
  if (!mesh)
    return out;
  const Triangulation covering = mesh->release();
  out.status = covering.status;
  out.stats = covering.stats;
  out.stats.inputPoints = count_;
  out.stats.nonFinitePoints = nonFinite_;
  out.stats.duplicatesMerged = duplicates_;
  out.stats.closePointsSkipped = close_;
  out.stats.insertedPoints = points_.size();
  out.imagePoints = covering_.size() - points_.size();
  out.margin = margin_;
  if (out.status == Status::Ok)
    extract(covering, out);
  out.stats.tetrahedra = out.numberOfTetrahedra();
  out.wraps = wraps_;
  out.representative.assign(representative_.begin(), representative_.end());
  return out;
}

PeriodicTriangulation triangulatePeriodic(
  const double* xyz, std::size_t count, const PeriodicBox& box, const Options& options)
{
  return PeriodicDelaunay(xyz, count, box, options).run();
}

} // namespace fd3
