// fd3::haloVertices, the exchange of the distributed filter, simulated in one process: every
// piece tetrahedralizes its own points plus the halo the others send it, keeps the tetrahedra
// whose lexicographically smallest vertex it owns (the lowest piece holding a copy of it), and the
// pieces together are the one-piece tetrahedralization, each tetrahedron exactly once. Weighted
// points too: the regular tetrahedralization, with each point hidden by the piece that owns it
// exactly where the whole set hides it.
#include "CoreTestUtilities.h"
#include "ExactValidator.h"
#include "PointSets.h"
#include "fd3/Distributed.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace
{
using Coordinates = std::array<double, 3>;

Coordinates at(const fd3test::Points& p, std::size_t id)
{
  return {p[3 * id], p[3 * id + 1], p[3 * id + 2]};
}

fd3::Bounds boxOf(const fd3test::Points& p, const std::vector<std::uint32_t>& ids)
{
  fd3::Bounds box;
  for (const std::uint32_t id : ids)
    box.include(&p[3 * id]);
  return box;
}

/// Weighted points: every point's weight, and the largest.
struct Weights
{
  std::vector<double> of;
  double heaviest = -HUGE_VAL;

  explicit Weights(std::vector<double> weights = {}) : of(std::move(weights))
  {
    for (double w : of)
      heaviest = std::max(heaviest, w);
  }
};

struct Piece
{
  std::vector<std::uint32_t> ids; ///< input ids: its own points, then the halo received
  std::size_t own = 0;
  std::vector<double> xyz;
  std::vector<double> weights; ///< weighted points only
  std::unique_ptr<fd3::IncrementalDelaunay> mesh;

  void append(const fd3test::Points& p, const Weights& w, const std::vector<std::uint32_t>& more)
  {
    for (std::uint32_t id : more)
    {
      ids.push_back(id);
      xyz.insert(xyz.end(), p.begin() + 3 * id, p.begin() + 3 * id + 3);
      if (!w.of.empty())
        weights.push_back(w.of[id]);
    }
  }
  const double* weightsFrom(std::size_t k) const
  {
    return weights.empty() ? nullptr : weights.data() + k;
  }
};

/// The result of the pieces together: the tetrahedra (as input ids of first copies) and the hidden
/// points (input ids, ascending), and the size of the halos.
struct Distributed
{
  std::vector<std::uint32_t> tetrahedra;
  std::vector<std::uint32_t> hidden;
  std::size_t halo = 0;
};

/// What each piece receives from the others (input ids): every piece's halo for every other box,
/// or all its points where it has no tetrahedron yet.
std::vector<std::vector<std::uint32_t>> exchangeHalos(
  const std::vector<Piece>& pieces, const std::vector<fd3::Bounds>& boxes, double heaviest)
{
  const int pieceCount = static_cast<int>(pieces.size());
  std::vector<std::vector<std::uint32_t>> received(pieceCount);
  for (int from = 0; from < pieceCount; ++from)
  {
    const Piece& piece = pieces[from];
    const fd3::Triangulation t = piece.mesh->snapshot();
    std::vector<std::vector<std::uint32_t>> halo(pieceCount);
    if (t.status == fd3::Status::Ok)
    {
      halo = piece.mesh->haloVertices(boxes, heaviest);
      EXPECT_EQ(halo, fd3::haloVertices(piece.xyz.data(), piece.weightsFrom(0), t, boxes, heaviest))
        << "live mesh and snapshot";
    }
    else
    {
      for (auto& ids : halo)
      {
        for (std::uint32_t k = 0; k < piece.own; ++k)
          ids.push_back(k);
      }
    }
    for (int to = 0; to < pieceCount; ++to)
    {
      for (std::uint32_t local : halo[to])
      {
        if (to != from)
          received[to].push_back(piece.ids[local]);
      }
    }
  }
  return received;
}

/// What the pieces keep, all pieces together.
Distributed distributedRun(
  const fd3test::Points& p, const Weights& w, const std::vector<int>& pieceOf, int pieceCount)
{
  const fd3::Frame frame = fd3test::frameOf(p);
  std::vector<Piece> pieces(pieceCount);
  for (std::uint32_t i = 0; i < pieceOf.size(); ++i)
  {
    pieces[pieceOf[i]].ids.push_back(i);
  }
  std::vector<fd3::Bounds> boxes;
  for (Piece& piece : pieces)
  {
    piece.own = piece.ids.size();
    std::vector<std::uint32_t> own;
    own.swap(piece.ids);
    piece.append(p, w, own);
    piece.mesh = std::make_unique<fd3::IncrementalDelaunay>(
      piece.xyz.data(), piece.own, fd3::Options(), frame, 0, piece.weightsFrom(0));
    boxes.push_back(boxOf(p, piece.ids));
  }
  const std::vector<std::vector<std::uint32_t>> received = exchangeHalos(pieces, boxes, w.heaviest);
  const std::vector<std::uint32_t> copy = fd3test::firstCopies(p);
  Distributed out;
  for (int j = 0; j < pieceCount; ++j)
  {
    Piece& piece = pieces[j];
    out.halo += received[j].size();
    piece.append(p, w, received[j]);
    piece.mesh->add(
      piece.xyz.data() + 3 * piece.own, received[j].size(), piece.weightsFrom(piece.own));
    const fd3::Triangulation t = piece.mesh->release();
    if (t.status != fd3::Status::Ok)
    {
      continue;
    }
    for (const std::uint32_t h : t.hidden)
    {
      if (h < piece.own)
        out.hidden.push_back(piece.ids[h]);
    }
    // The lowest piece holding each vertex's position owns it.
    std::vector<int> holder(piece.ids.size(), pieceCount);
    for (std::size_t k = 0; k < piece.ids.size(); ++k)
    {
      const std::uint32_t v = t.representative[k];
      if (v != fd3::kNoPoint && at(p, piece.ids[k]) == at(p, piece.ids[v]))
        holder[v] = std::min(holder[v], pieceOf[piece.ids[k]]);
    }
    for (std::size_t tet = 0; tet < t.numberOfTetrahedra(); ++tet)
    {
      const std::uint32_t* v = t.tetrahedra.data() + 4 * tet;
      const std::uint32_t smallest =
        *std::min_element(v, v + 4, [&](std::uint32_t a, std::uint32_t b) {
          return at(p, piece.ids[a]) < at(p, piece.ids[b]);
        });
      if (holder[smallest] == j)
      {
        for (int k = 0; k < 4; ++k)
          out.tetrahedra.push_back(copy[piece.ids[v[k]]]);
      }
    }
  }
  std::sort(out.hidden.begin(), out.hidden.end());
  return out;
}

std::vector<int> slabs(const fd3test::Points& p, int count)
{
  std::vector<std::uint32_t> order(p.size() / 3);
  for (std::uint32_t i = 0; i < order.size(); ++i)
    order[i] = i;
  std::stable_sort(order.begin(), order.end(),
    [&](std::uint32_t a, std::uint32_t b) { return p[3 * a] < p[3 * b]; });
  std::vector<int> pieceOf(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    pieceOf[order[k]] = static_cast<int>(k * count / order.size());
  return pieceOf;
}

void expectSameAsOnePiece(const fd3test::Points& p, const std::vector<int>& pieceOf, int pieceCount,
  const Weights& w = Weights())
{
  const fd3::Triangulation whole =
    fd3::triangulate(p.data(), w.of.empty() ? nullptr : w.of.data(), p.size() / 3);
  ASSERT_EQ(whole.status, fd3::Status::Ok);
  const Distributed pieces = distributedRun(p, w, pieceOf, pieceCount);
  const auto copy = fd3test::firstCopies(p);
  fd3::IdArray reference(whole.tetrahedra.size());
  std::transform(whole.tetrahedra.begin(), whole.tetrahedra.end(), reference.begin(),
    [&](std::uint32_t id) { return copy[id]; });
  // Equal sorted lists, so no tetrahedron is kept twice or missed.
  EXPECT_EQ(
    fd3test::canonicalTetrahedra(pieces.tetrahedra), fd3test::canonicalTetrahedra(reference));
  EXPECT_EQ(pieces.hidden, whole.hidden);
  fd3test::ValidityOptions check;
  check.weights = w.of.empty() ? nullptr : w.of.data();
  check.hidden = pieces.hidden;
  const auto report = fd3test::checkTriangulation(p.data(), p.size() / 3, pieces.tetrahedra, check);
  EXPECT_TRUE(report.valid()) << report.summary();
  testing::Test::RecordProperty("halo", std::to_string(pieces.halo));
}

/// Radii drawn in [lo, hi], squared, and `heavy` radii of `large` among them.
Weights randomRadii(
  std::size_t n, double lo, double hi, std::size_t heavy, double large, std::uint64_t seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> radius(lo, hi);
  std::vector<double> w(n);
  for (double& x : w)
    x = std::pow(radius(random), 2);
  for (std::size_t k = 0; k < heavy; ++k)
    w[random() % n] = large * large;
  return Weights(std::move(w));
}
} // namespace

TEST(Halo, SlabsGiveTheOnePieceTetrahedraOnEveryPointSet)
{
  for (const std::string& kind : fd3test::pointSetNames())
  {
    SCOPED_TRACE(kind);
    const fd3test::Points p = fd3test::generate(kind, 6000, 5);
    for (int pieces : {2, 3, 4})
    {
      SCOPED_TRACE(pieces);
      expectSameAsOnePiece(p, slabs(p, pieces), pieces);
    }
  }
}

// Pieces that overlap everywhere (each point on a random piece), one piece holding everything,
// and an empty piece: the boxes then tell little, but the result must not change.
TEST(Halo, AnyDistributionGivesTheOnePieceTetrahedra)
{
  for (const std::string& kind : {"cube", "lattice", "clusters", "sphere", "terrain"})
  {
    SCOPED_TRACE(kind);
    const fd3test::Points p = fd3test::generate(kind, 3000, 9);
    std::mt19937 random(3);
    std::vector<int> scattered(p.size() / 3), allOnOne(p.size() / 3, 1), withEmpty = slabs(p, 3);
    for (int& piece : scattered)
      piece = static_cast<int>(random() % 3);
    for (int& piece : withEmpty)
      piece = piece == 1 ? 3 : piece;
    expectSameAsOnePiece(p, scattered, 3);
    expectSameAsOnePiece(p, allOnOne, 3);
    expectSameAsOnePiece(p, withEmpty, 4);
  }
}

// A piece with fewer than 4 points or coplanar ones has no tetrahedra to choose a halo from.
TEST(Halo, DegeneratePiecesSendEverything)
{
  fd3test::Points p = fd3test::generate("cube", 500, 4);
  std::vector<int> pieceOf = slabs(p, 2);
  const std::size_t n = p.size() / 3;
  for (double x : {0.2, 0.4, 0.6}) // 3 points of a third piece
  {
    p.insert(p.end(), {x, 0.5, 0.5});
    pieceOf.push_back(2);
  }
  for (int k = 0; k < 20; ++k) // and 20 coplanar ones of a fourth
  {
    p.insert(p.end(), {0.05 * k, 0.3 + 0.01 * (k % 7), 0.25});
    pieceOf.push_back(3);
  }
  ASSERT_EQ(pieceOf.size(), n + 23);
  expectSameAsOnePiece(p, pieceOf, 4);
}

// Weighted points: heavy points reach across the slabs' faces by power distance, far beyond
// their circumspheres, and hide the points of other pieces; a packing hides a quarter of them.
TEST(Halo, WeightedPiecesGiveTheOnePieceRegularTetrahedra)
{
  const fd3test::Points cube = fd3test::generate("cube", 4000, 11);
  for (int pieces : {2, 3, 4})
  {
    SCOPED_TRACE(pieces);
    expectSameAsOnePiece(
      cube, slabs(cube, pieces), pieces, randomRadii(4000, 0.001, 0.03, 0, 0, 12));
    expectSameAsOnePiece(
      cube, slabs(cube, pieces), pieces, randomRadii(4000, 0.001, 0.03, 6, 0.2, 13));
  }
  std::vector<double> radii;
  const fd3test::Points molecule = fd3test::molecule(3000, 14, radii);
  for (double& r : radii)
    r = (r + 1.4) * (r + 1.4);
  expectSameAsOnePiece(molecule, slabs(molecule, 3), 3, Weights(radii));
  std::mt19937 random(15);
  std::vector<int> scattered(cube.size() / 3);
  for (int& piece : scattered)
    piece = static_cast<int>(random() % 3);
  expectSameAsOnePiece(cube, scattered, 3, randomRadii(4000, 0.0, 0.05, 3, 0.3, 16));
}

TEST(Halo, WeightedPackingHidesAQuarterAcrossPieces)
{
  const std::size_t large = 3000, small = 1000;
  fd3test::Points p = fd3test::uniformCube(large, 21);
  std::vector<double> w(large, 0.1 * 0.1);
  std::mt19937_64 random(22);
  std::uniform_real_distribution<double> offset(-0.005, 0.005);
  for (std::size_t i = 0; i < small; ++i)
  {
    const std::size_t c = random() % large;
    for (int k = 0; k < 3; ++k)
      p.push_back(p[3 * c + k] + offset(random));
    w.push_back(0.001 * 0.001);
  }
  expectSameAsOnePiece(p, slabs(p, 4), 4, Weights(w));
}
