// The periodic tetrahedra placed for drawing (fd3/Periodic.h): each vertex moved from its input
// point by the offset less the point's wraps, a whole number of periods, and the positions that
// are not an input point's own made image points, once per point and shift.
#include "fd3/Periodic.h"

#include <array>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace fd3
{
namespace
{
struct Image
{
  std::uint32_t source;
  std::array<std::int32_t, 3> shift;

  bool operator==(const Image& other) const
  {
    return source == other.source && shift == other.shift;
  }
};

struct ImageHash
{
  std::size_t operator()(const Image& image) const
  {
    std::uint64_t h = image.source;
    for (const std::int32_t s : image.shift)
      h = (h ^ std::uint32_t(s)) * 0x9E3779B97F4A7C15ull;
    return std::size_t(h ^ (h >> 29));
  }
};
} // namespace

PeriodicPlacement placePeriodic(const double* xyz, std::size_t count,
  const PeriodicTriangulation& triangulation, const PeriodicBox& box)
{
  PeriodicPlacement placement;
  placement.tetrahedra.resize(triangulation.tetrahedra.size());
  std::unordered_map<Image, std::uint32_t, ImageHash> imageIds;
  for (std::size_t v = 0; v < triangulation.tetrahedra.size(); ++v)
  {
    const std::uint32_t id = triangulation.tetrahedra[v];
    Image image{id, {0, 0, 0}};
    bool moved = id >= count; // a piece's ghost
    for (int a = 0; a < 3; ++a)
    {
      image.shift[a] = std::int32_t(triangulation.offsets[3 * v + a]) -
        triangulation.wraps[3 * std::size_t(id) + a];
      moved = moved || image.shift[a] != 0;
    }
    if (!moved)
    {
      placement.tetrahedra[v] = id;
      continue;
    }
    if (count + imageIds.size() >= kNoPoint)
      throw std::length_error("more image points than 32-bit ids hold");
    const auto found = imageIds.emplace(image, std::uint32_t(count + imageIds.size()));
    placement.tetrahedra[v] = found.first->second;
    if (!found.second)
      continue;
    placement.imageSources.push_back(id);
    for (int a = 0; a < 3; ++a)
    {
      placement.imageShifts.push_back(image.shift[a]);
      const double period = box.hi[a] - box.lo[a];
      placement.imagePoints.push_back(
        xyz[3 * std::size_t(id) + a] + double(image.shift[a]) * period);
    }
  }
  return placement;
}

} // namespace fd3
