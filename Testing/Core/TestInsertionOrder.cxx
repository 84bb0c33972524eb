// The insertion order's curve: the properties that make consecutive points close.
#include "PointSets.h"
#include "insertion/InsertionOrder.h"
#include "system/Threads.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <random>
#include <vector>

namespace
{
using Cell = std::array<std::uint32_t, 3>;

bool shareAFace(const Cell& a, const Cell& b)
{
  int distance = 0;
  for (int k = 0; k < 3; ++k)
    distance += std::abs(static_cast<int>(a[k]) - static_cast<int>(b[k]));
  return distance == 1;
}

// Every cell of the aligned block of 2^bits cells a side at `corner` must take one of 8^bits
// consecutive positions, all distinct, each next to the one before it.
void expectBlockIsOneStretchOfTheCurve(const Cell& corner, int bits)
{
  const std::uint32_t side = 1u << bits;
  const std::uint32_t stretch = side * side * side;
  const std::uint32_t first = fd3::hilbertIndex(corner[0], corner[1], corner[2]) & ~(stretch - 1);
  std::vector<Cell> cellAt(stretch);
  std::vector<bool> seen(stretch, false);
  for (std::uint32_t x = 0; x < side; ++x)
    for (std::uint32_t y = 0; y < side; ++y)
      for (std::uint32_t z = 0; z < side; ++z)
      {
        const Cell cell = {corner[0] + x, corner[1] + y, corner[2] + z};
        const std::uint32_t position = fd3::hilbertIndex(cell[0], cell[1], cell[2]);
        ASSERT_GE(position, first);
        ASSERT_LT(position - first, stretch);
        ASSERT_FALSE(seen[position - first]) << "two cells at position " << position;
        seen[position - first] = true;
        cellAt[position - first] = cell;
      }
  for (std::uint32_t i = 1; i < stretch; ++i)
    ASSERT_TRUE(shareAFace(cellAt[i - 1], cellAt[i]))
      << "positions " << first + i - 1 << " and " << first + i;
}
} // namespace

TEST(InsertionOrder, HilbertCurveStepsToANeighbourAndFillsEveryAlignedBlock)
{
  // The whole curve, coarsely (its top three levels), and stretches of it at the finest levels.
  for (const std::uint32_t x : {0u, 128u, 512u, 896u})
    for (const std::uint32_t y : {0u, 384u, 896u})
      for (const std::uint32_t z : {0u, 640u, 896u})
        expectBlockIsOneStretchOfTheCurve({x, y, z}, 5);
  std::vector<Cell> coarse(512);
  std::vector<bool> seen(512, false);
  for (std::uint32_t c = 0; c < 512; ++c)
  {
    const Cell corner = {(c & 7u) << 7, ((c >> 3) & 7u) << 7, (c >> 6) << 7};
    const std::uint32_t position = fd3::hilbertIndex(corner[0], corner[1], corner[2]) >> 21;
    ASSERT_FALSE(seen[position]) << "two coarse cells at position " << position;
    seen[position] = true;
    coarse[position] = {c & 7u, (c >> 3) & 7u, c >> 6};
  }
  for (std::uint32_t i = 1; i < 512; ++i)
    EXPECT_TRUE(shareAFace(coarse[i - 1], coarse[i])) << "coarse positions " << i - 1 << ", " << i;
  EXPECT_EQ(fd3::hilbertIndex(0, 0, 0), 0u);
}

// The plan is the same for any number of threads, also where dense clusters put thousands of
// points in one cell of the curve's grid: those runs are refined after the others, each on one
// thread, shared out by length. 45,000 points in each of 20 cubes no wider than a cell put 5,625 or
// more in some cell, more than a long run needs (4096).
TEST(InsertionOrder, SamePlanForAnyNumberOfThreadsAlsoWithDenseClusters)
{
  const fd3test::Points p = fd3test::generate("clusters", 1000000, 3);
  const std::size_t n = p.size() / 3;
  fd3::IdArray ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  std::vector<std::uint16_t> key(n);
  std::mt19937 rng(5);
  for (std::uint16_t& k : key)
    k = static_cast<std::uint16_t>(rng());
  const fd3::Bounds box = fd3::finiteBounds(p.data(), n);
  fd3::InsertionPlan reference;
  for (const int threads : {1, 2, 5, 16})
  {
    fd3::ThreadTeam team(threads);
    fd3::InsertionPlan plan =
      fd3::planInsertion(p.data(), key.data(), ids, box, fd3::InsertionOrder::Brio, 7, team);
    ASSERT_EQ(plan.order.size(), n);
    if (threads == 1)
    {
      reference = std::move(plan);
      continue;
    }
    EXPECT_TRUE(plan.order == reference.order) << threads << " threads";
    EXPECT_EQ(plan.roundStarts, reference.roundStarts) << threads << " threads";
    EXPECT_EQ(plan.duplicates, reference.duplicates) << threads << " threads";
  }
}
