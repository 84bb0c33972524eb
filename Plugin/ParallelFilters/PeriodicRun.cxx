/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "PeriodicRun.h"

#include "FilterInput.h"

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace fd3vtk
{
namespace
{
/// The name of the values that GhostValues() sends.
constexpr const char* kGhostValues = "FastDelaunay3DGhostValues";

/// Which of the lists hold something.
std::vector<bool> NonEmpty(const std::vector<std::vector<std::uint32_t>>& lists)
{
  std::vector<bool> nonEmpty(lists.size());
  for (std::size_t r = 0; r < lists.size(); ++r)
  {
    nonEmpty[r] = !lists[r].empty();
  }
  return nonEmpty;
}

/// Appends the input ids (kInputIds) of the points of `data` to `ids`.
void AppendInputIds(vtkPointData* data, std::vector<std::uint32_t>& ids)
{
  vtkDataArray* inputIds = data->GetArray(kInputIds);
  for (vtkIdType i = 0; i < inputIds->GetNumberOfTuples(); ++i)
  {
    const double id = inputIds->GetComponent(i, 0);
    if (!(id < double(std::numeric_limits<std::uint32_t>::max())))
    {
      throw std::length_error("more points than the periodic kernel's 32-bit ids hold");
    }
    ids.push_back(static_cast<std::uint32_t>(id));
  }
}
} // namespace

fd3::Bounds GlobalFiniteBounds(vtkMultiProcessController* controller, vtkPoints* points)
{
  fd3::Bounds mine;
  if (points)
  {
    std::vector<double> converted;
    const double* xyz = CoordinatesAsDoubles(points, converted);
    mine = fd3::finiteBounds(xyz, static_cast<std::size_t>(points->GetNumberOfPoints()), 1);
  }
  fd3::Bounds all;
  controller->AllReduce(mine.lo, all.lo, 3, vtkCommunicator::MIN_OP);
  controller->AllReduce(mine.hi, all.hi, 3, vtkCommunicator::MAX_OP);
  return all;
}

PeriodicRun::PeriodicRun(DistributedRun& run, const fd3::PeriodicBox& box)
  : Distributed(run), Box(box), Exchange(run.Ranks)
{}

bool PeriodicRun::Redistribute(vtkDataSet* input, vtkPoints* points)
{
  vtkNew<vtkDoubleArray> places;
  places->SetNumberOfComponents(3);
  if (!this->Distributed.Ranks.Local([&] {
        const auto count = static_cast<std::size_t>(points ? points->GetNumberOfPoints() : 0);
        std::vector<double> converted, wrapped;
        const double* xyz = count ? CoordinatesAsDoubles(points, converted) : nullptr;
        if (!fd3::periodicPlaces(xyz, count, this->Box, wrapped))
        {
          throw std::runtime_error("a point lies more than 2^30 periods from the box");
        }
        places->SetNumberOfTuples(static_cast<vtkIdType>(count));
        std::copy(wrapped.begin(), wrapped.end(), places->GetPointer(0));
        return true;
      }))
  {
    return false;
  }
  return this->Distributed.Redistribute(input, points, {}, places);
}

bool PeriodicRun::Run(
  const std::function<bool(const fd3::PeriodicPiece&, double& widerHalo)>& piece)
{
  RankGroup& ranks = this->Distributed.Ranks;
  fd3::Bounds region;
  std::size_t finite = 0;
  if (!ranks.Local([&] {
        const Coordinates& own = this->Distributed.OwnXyz();
        if (!fd3::periodicPlaces(own.data(), this->Distributed.OwnCount(), this->Box, this->Places))
        {
          throw std::runtime_error("a point lies more than 2^30 periods from the box");
        }
        finite = this->Distributed.OwnFinite();
        for (std::size_t i = 0; i < finite; ++i)
        {
          region.include(&this->Places[3 * i]);
        }
        return true;
      }))
  {
    return false;
  }
  this->Regions.assign(ranks.Size, fd3::Bounds());
  ranks.Controller->AllGather(region.lo, this->Regions[0].lo, 6);
  const auto mine = static_cast<vtkIdType>(finite);
  vtkIdType all = 0;
  ranks.Controller->AllReduce(&mine, &all, 1, vtkCommunicator::SUM_OP);

  fd3::PeriodicPiece own;
  own.own = this->Distributed.OwnCount();
  own.region = region;
  own.points = static_cast<std::size_t>(all);
  for (const fd3::Bounds& r : this->Regions)
  {
    own.extent.include(r);
  }
  // Each rank's halo, widened where its piece asks: the others' pieces stand as they are.
  std::vector<double> halos(ranks.Size, fd3::firstPeriodicHalo(this->Box, own.points, own.extent));
  std::vector<double> wider(ranks.Size, 0.0);
  std::vector<char> again(ranks.Size, 1);
  this->Sent.assign(ranks.Size, {});
  for (this->Exchanges = 1;; ++this->Exchanges)
  {
    double mine = 0;
    own.halo = halos[ranks.Rank];
    if (!this->ExchangeGhosts(halos, again) || !ranks.Local([&] {
          own.ids = this->Ids.data();
          return !again[ranks.Rank] || piece(own, mine);
        }))
    {
      return false;
    }
    ranks.Controller->AllGather(&mine, wider.data(), 1);
    bool any = false;
    for (int r = 0; r < ranks.Size; ++r)
    {
      again[r] = wider[r] > 0;
      halos[r] = again[r] ? wider[r] : halos[r];
      any = any || again[r];
    }
    if (!any)
    {
      const auto ghosts = static_cast<vtkIdType>(this->Xyz.size() / 3 - own.own);
      ranks.Controller->AllReduce(&ghosts, &this->GhostPoints, 1, vtkCommunicator::SUM_OP);
      return true;
    }
  }
}

bool PeriodicRun::ExchangeGhosts(const std::vector<double>& halos, const std::vector<char>& to)
{
  RankGroup& ranks = this->Distributed.Ranks;
  std::vector<bool> sendTo(ranks.Size, false);
  if (!ranks.Local([&] {
        const std::size_t finite = this->Distributed.OwnFinite();
        for (int r = 0; r < ranks.Size; ++r)
        {
          if (!to[r])
          {
            continue;
          }
          this->Sent[r].clear();
          for (std::uint32_t i = 0; r != ranks.Rank && i < finite; ++i)
          {
            if (fd3::periodicImageWithin(
                  &this->Places[3 * i], this->Box, this->Regions[r], halos[r]))
            {
              this->Sent[r].push_back(i);
            }
          }
          sendTo[r] = !this->Sent[r].empty();
        }
        return true;
      }))
  {
    return false;
  }
  Received received;
  const Coordinates& own = this->Distributed.OwnXyz();
  if (!this->Exchange.Send(
        sendTo,
        [&](int r) {
          std::vector<double> xyz;
          for (const std::uint32_t i : this->Sent[r])
          {
            xyz.insert(xyz.end(), &own[3 * i], &own[3 * i] + 3);
          }
          return this->Distributed.HaloPart(this->Sent[r], xyz);
        },
        received))
  {
    return false;
  }
  return ranks.Local([&] {
    if (!to[ranks.Rank]) // no rank sent to this one: its ghosts stand
    {
      return true;
    }
    this->Ghosts = std::move(received);
    this->Xyz.assign(own.begin(), own.end());
    this->Ids.clear();
    AppendInputIds(this->Distributed.OwnData(), this->Ids);
    for (const auto& part : this->Ghosts.Parts)
    {
      std::vector<double> converted;
      const double* xyz = CoordinatesAsDoubles(part->GetPoints(), converted);
      this->Xyz.insert(this->Xyz.end(), xyz, xyz + 3 * part->GetNumberOfPoints());
      AppendInputIds(part->GetPointData(), this->Ids);
    }
    return true;
  });
}

bool PeriodicRun::GhostValues(const std::vector<double>& own, std::vector<double>& ghosts)
{
  Received values;
  if (!this->Exchange.Send(
        NonEmpty(this->Sent),
        [&](int r) {
          const auto count = static_cast<vtkIdType>(this->Sent[r].size());
          vtkNew<vtkPoints> points; // where each value goes is its place in the part
          points->SetNumberOfPoints(count);
          points->GetData()->Fill(0);
          vtkNew<vtkDoubleArray> sent;
          sent->SetName(kGhostValues);
          sent->SetNumberOfValues(count);
          for (vtkIdType k = 0; k < count; ++k)
          {
            sent->SetValue(k, own[this->Sent[r][static_cast<std::size_t>(k)]]);
          }
          auto part = vtkSmartPointer<vtkPolyData>::New();
          part->SetPoints(points);
          part->GetPointData()->AddArray(sent);
          return part;
        },
        values))
  {
    return false;
  }
  return this->Distributed.Ranks.Local([&] {
    if (values.Senders != this->Ghosts.Senders)
    {
      throw std::logic_error("the ghosts' values came from other ranks than the ghosts");
    }
    ghosts.clear();
    for (const auto& part : values.Parts)
    {
      vtkDataArray* array = part->GetPointData()->GetArray(kGhostValues);
      for (vtkIdType k = 0; k < array->GetNumberOfTuples(); ++k)
      {
        ghosts.push_back(array->GetComponent(k, 0));
      }
    }
    return true;
  });
}

vtkSmartPointer<vtkPointData> PeriodicRun::PointData() const
{
  std::vector<vtkPointData*> parts{ this->Distributed.OwnData() };
  for (const auto& part : this->Ghosts.Parts)
  {
    parts.push_back(part->GetPointData());
  }
  return GatherPointData(parts);
}
} // namespace fd3vtk
