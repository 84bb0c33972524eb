#include "Triangulator.h"

#include <array>
#include <chrono>
#include <sstream>
#include <utility>

namespace fd3
{

Triangulator::Triangulator(std::vector<double> xyz, const Options& options, Statistics& stats)
  : xyz_(std::move(xyz))
  , options_(options)
  , stats_(stats)
  , rng_(options.randomSeed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)
{
  const std::size_t n = xyz_.size() / 3;
  mesh_.reserve(7 * n + 64);
  vertexTet_.assign(n + 1, 0);
  grid_.build(xyz_.data(), n, options.pointsPerCell);
  predicates_.adaptTo(xyz_.data(), n);
}

void Triangulator::releaseWorkspace()
{
  std::vector<double>().swap(xyz_);
  std::vector<TetId>().swap(vertexTet_);
  std::vector<std::uint32_t>().swap(vertexStamp_);
  grid_ = BackgroundGrid();
  for (auto* scratch : {&cavity_, &rejected_, &created_})
    std::vector<TetId>().swap(*scratch);
  std::vector<BoundaryFacet>().swap(boundary_);
  std::vector<std::pair<FaceCode, std::uint32_t>>().swap(interiorFaces_);
}

std::uint32_t Triangulator::nextRandom()
{
  // xorshift64*: cheap, seeded, and good enough to break the walk's symmetries.
  rng_ ^= rng_ >> 12;
  rng_ ^= rng_ << 25;
  rng_ ^= rng_ >> 27;
  return static_cast<std::uint32_t>((rng_ * 0x2545F4914F6CDD1Dull) >> 32);
}

// The first tetrahedron and the four ghosts that close its hull.
void Triangulator::start()
{
  VertId v[4] = {0, 1, 2, 3};
  if (predicates_.orient3d(point(0), point(1), point(2), point(3)) < 0)
    std::swap(v[0], v[1]);
  const TetId t = mesh_.allocate();
  mesh_.create(t, v);
  // Ghost i sits on the face opposite v[i], listed so that (face, v[i]) is an odd permutation of
  // t: the face normal then points away from v[i], out of the hull.
  static constexpr int kOutwardFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  TetId ghost[4];
  for (int i = 0; i < 4; ++i)
  {
    ghost[i] = mesh_.allocate();
    const VertId face[4] = {v[kOutwardFace[i][0]], v[kOutwardFace[i][1]], v[kOutwardFace[i][2]], kInfinite};
    mesh_.create(ghost[i], face);
    mesh_.link(faceCode(t, i), faceCode(ghost[i], 3));
  }
  // Ghosts meet along the edges of t: ghost i's face opposite its vertex k is the edge of
  // ghost i's hull face without that vertex, shared with the ghost on the other side of that edge.
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
    {
      const VertId missing = mesh_.vertex(ghost[i], k);
      int j = 0;
      while (v[j] != missing)
        ++j;
      // The other ghost holding the edge is the one opposite `missing`; in it, the face opposite
      // v[i] is the one on the edge.
      int kk = 0;
      while (mesh_.vertex(ghost[j], kk) != v[i])
        ++kk;
      mesh_.setNeighbor(faceCode(ghost[i], k), faceCode(ghost[j], kk));
    }
  for (int i = 0; i < 4; ++i)
  {
    vertexTet_[v[i]] = t;
    if (grid_.enabled())
      grid_.markInserted(point(v[i]), v[i]);
  }
  lastCreated_ = t;
  stats_.insertedPoints = 4;
}

namespace
{
// Phase times are measured on one insertion in kSampling and scaled up: reading the clock around
// every phase of every insertion would cost more than the shortest phases.
constexpr VertId kSampling = 16;

class PhaseClock
{
public:
  explicit PhaseClock(bool on)
    : on_(on)
  {
    if (on_)
      last_ = std::chrono::steady_clock::now();
  }
  void lap(double& seconds)
  {
    if (!on_)
      return;
    const auto now = std::chrono::steady_clock::now();
    seconds += kSampling * std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }

private:
  bool on_;
  std::chrono::steady_clock::time_point last_;
};
} // namespace

Triangulator::Outcome Triangulator::insert(VertId v)
{
  PhaseClock clock(v % kSampling == 0);
  const TetId base = locate(v);
  clock.lap(stats_.secondsLocate);
  for (int i = 0; i < 4; ++i)
  {
    const VertId u = mesh_.vertex(base, i);
    if (u != kInfinite && point(u)[0] == point(v)[0] && point(u)[1] == point(v)[1] &&
      point(u)[2] == point(v)[2])
    {
      duplicateOf_ = u;
      return Outcome::Duplicate;
    }
  }
  digCavity(base, v);
  if (options_.tolerance > 0)
  {
    if (const VertId near = vertexWithin(options_.tolerance * options_.tolerance, v); near != kInfinite)
    {
      undoCavity();
      duplicateOf_ = near;
      return Outcome::TooClose;
    }
  }
  correctCavity(v);
  clock.lap(stats_.secondsCavity);
  fillCavity(v);
  clock.lap(stats_.secondsFill);
  if (grid_.enabled())
    grid_.markInserted(point(v), v);
  ++stats_.insertedPoints;
  return Outcome::Inserted;
}

std::string Triangulator::checkMesh()
{
  std::ostringstream err;
  for (TetId t = 0; t < mesh_.slots(); ++t)
  {
    if (mesh_.isDead(t))
      continue;
    VertId tv[4], nv[4];
    mesh_.vertices(t, tv);
    if (mesh_.flags(t) != 0)
      err << "tet " << t << " has stale cavity flags\n";
    for (int f = 0; f < 4; ++f)
    {
      const FaceCode back = mesh_.neighbor(t, f);
      if (back == kUnlinked || mesh_.isDead(tetOf(back)) || mesh_.across(back) != faceCode(t, f))
      {
        err << "tet " << t << " face " << f << ": adjacency not symmetric\n";
        continue;
      }
      // The shared face must carry the same three vertices.
      mesh_.vertices(tetOf(back), nv);
      for (int k = 0; k < 4; ++k)
      {
        if (k == f)
          continue;
        bool found = false;
        for (int m = 0; m < 4; ++m)
          found |= (m != faceOf(back) && nv[m] == tv[k]);
        if (!found)
          err << "tet " << t << " face " << f << ": neighbour does not share the face\n";
      }
    }
    if (mesh_.isGhost(t))
      continue;
    if (predicates_.orient3d(point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])) <= 0)
      err << "tet " << t << " not positively oriented\n";
    for (int f = 0; f < 4 && options_.volumeThreshold <= 0; ++f)
    {
      const FaceCode back = mesh_.neighbor(t, f);
      const TetId n = tetOf(back);
      if (mesh_.isGhost(n))
        continue;
      const VertId opposite = mesh_.vertex(n, faceOf(back));
      if (predicates_.inSphere(point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3]),
            point(opposite)) > 0)
        err << "tet " << t << " face " << f << ": not locally Delaunay\n";
    }
  }
  return err.str();
}

} // namespace fd3
