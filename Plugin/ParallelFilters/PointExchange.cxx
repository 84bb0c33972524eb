/*=========================================================================
  FastDelaunay3D
  SPDX-License-Identifier: BSD-3-Clause
=========================================================================*/
#include "PointExchange.h"

#include "vtkCommunicator.h"
#include "vtkDIYUtilities.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributesFieldList.h"
#include "vtkFieldData.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

// clang-format off
#include "vtk_diy2.h"
#include VTK_DIY2(diy/assigner.hpp)
#include VTK_DIY2(diy/link.hpp)
#include VTK_DIY2(diy/master.hpp)
#include VTK_DIY2(diy/mpi.hpp)
// clang-format on

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fd3vtk
{
namespace
{
/// What the exchange brought, in rank order.
void Take(diy::Master& master, const RankGroup& ranks, Received& received)
{
  std::vector<vtkSmartPointer<vtkPolyData>> byRank(ranks.Size);
  master.foreach ([&](void*, const diy::Master::ProxyWithLink& proxy) {
    for (const diy::BlockID& from : proxy.link()->neighbors())
    {
      if (proxy.incoming(from.gid))
      {
        vtkDataArray* xyz = nullptr;
        vtkFieldData* values = nullptr;
        proxy.dequeue<vtkDataArray*>(from.gid, xyz);
        proxy.dequeue<vtkFieldData*>(from.gid, values);
        byRank[from.gid] = vtkSmartPointer<vtkPolyData>::New();
        byRank[from.gid]->SetPoints(vtkNew<vtkPoints>());
        byRank[from.gid]->GetPoints()->SetData(vtkSmartPointer<vtkDataArray>::Take(xyz));
        byRank[from.gid]->GetPointData()->ShallowCopy(vtkSmartPointer<vtkFieldData>::Take(values));
      }
    }
  });
  for (int r = 0; r < ranks.Size; ++r)
  {
    if (byRank[r] && byRank[r]->GetNumberOfPoints() > 0)
    {
      received.Parts.push_back(byRank[r]);
      received.Senders.push_back(r);
    }
  }
}
} // namespace

/// The point data of `parts` one after the other: the arrays that all of them have, as
/// vtkAppendFilter keeps them.
vtkSmartPointer<vtkPointData> GatherPointData(const std::vector<vtkPointData*>& parts)
{
  vtkDataSetAttributesFieldList arrays(static_cast<int>(parts.size()));
  vtkIdType count = 0;
  for (vtkPointData* part : parts)
  {
    part == parts[0] ? arrays.InitializeFieldList(part) : arrays.IntersectFieldList(part);
    count += part->GetNumberOfTuples();
  }
  auto data = vtkSmartPointer<vtkPointData>::New();
  data->CopyAllocate(arrays, count);
  vtkIdType next = 0;
  for (std::size_t k = 0; k < parts.size(); ++k)
  {
    const vtkIdType n = parts[k]->GetNumberOfTuples();
    arrays.CopyData(static_cast<int>(k), parts[k], 0, n, data, next);
    next += n;
  }
  return data;
}

bool PointExchange::BalancedCuts(
  vtkDataArray* coordinates, const std::vector<vtkIdType>& finite, SpaceCuts& cuts)
{
  constexpr double kSample = 1 << 18; // parts within about 1% of the mean
  vtkMultiProcessController* controller = this->Ranks.Controller;
  const vtkIdType local = static_cast<vtkIdType>(finite.size());
  vtkIdType total = 0;
  controller->AllReduce(&local, &total, 1, vtkCommunicator::SUM_OP);
  std::vector<double> sample;
  if (!this->Ranks.Local([&] {
        const auto mine = static_cast<std::size_t>(std::ceil(kSample * local / double(total)));
        sample.resize(3 * std::min(mine, finite.size()));
        for (std::size_t k = 0; k < sample.size() / 3; ++k)
        {
          coordinates->GetTuple(finite[k * finite.size() / (sample.size() / 3)], &sample[3 * k]);
        }
        return true;
      }))
  {
    return false;
  }
  std::vector<vtkIdType> lengths(this->Ranks.Size), offsets(this->Ranks.Size);
  const vtkIdType length = static_cast<vtkIdType>(sample.size());
  controller->AllGather(&length, lengths.data(), 1);
  std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  std::vector<std::array<double, 3>> all;
  if (!this->Ranks.Local([&] {
        all.resize(static_cast<std::size_t>(offsets.back() + lengths.back()) / 3);
        return true;
      }))
  {
    return false;
  }
  controller->AllGatherV(sample.data(), all.data()->data(), length, lengths.data(), offsets.data());
  return this->Ranks.Local([&] {
    cuts.Split(all.begin(), all.end(), 0, this->Ranks.Size);
    return true;
  });
}

bool PointExchange::Send(const std::vector<bool>& sendTo,
  const std::function<vtkSmartPointer<vtkPolyData>(int rank)>& part, Received& received)
{
  const int rank = this->Ranks.Rank, size = this->Ranks.Size;
  diy::mpi::communicator comm = vtkDIYUtilities::GetCommunicator(this->Ranks.Controller);
  std::vector<int> sends(size);
  for (int r = 0; r < size; ++r)
  {
    sends[r] = r != rank && sendTo[r];
  }
  std::vector<std::vector<int>> allSends;
  diy::mpi::all_gather(comm, sends, allSends);
  diy::Master master(comm, 1, -1, nullptr, [](void*) {});
  diy::ContiguousAssigner assigner(size, size);
  auto* link = new diy::Link(); // the master's
  for (int r = 0; r < size; ++r)
  {
    if (allSends[rank][r] || allSends[r][rank])
    {
      link->add_neighbor(diy::BlockID(r, assigner.rank(r)));
    }
  }
  int block = 0; // DIY's one block per rank; its content is not used
  master.add(rank, &block, link);
  if (!this->Ranks.Local([&] {
        master.foreach ([&](void*, const diy::Master::ProxyWithLink& proxy) {
          for (const diy::BlockID& to : proxy.link()->neighbors())
          {
            if (sends[to.gid])
            {
              vtkSmartPointer<vtkPolyData> points = part(to.gid);
              proxy.enqueue<vtkDataArray*>(to, points->GetPoints()->GetData());
              proxy.enqueue<vtkFieldData*>(to, points->GetPointData());
            }
          }
        });
        return true;
      }))
  {
    return false;
  }
  master.exchange();
  return this->Ranks.Local([&] {
    Take(master, this->Ranks, received);
    return true;
  });
}
} // namespace fd3vtk
