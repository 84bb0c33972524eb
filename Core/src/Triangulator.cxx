#include "Triangulator.h"

#include <chrono>
#include <utility>

namespace fd3
{

Triangulator::Triangulator(
  std::vector<Vertex> vertices, const Box& box, const Options& options, Statistics& stats)
  : vertices_(std::move(vertices))
  , options_(options)
  , stats_(stats)
  , rng_(options.randomSeed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull)
{
  const std::size_t n = vertexCount();
  mesh_.reserve(7 * n + 64); // uniform points make 6.7 per vertex; reserveForAll() corrects it
  grid_.build(n, box, options.pointsPerCell);
  predicates_.adaptTo(vertices_[0].xyz, n, sizeof(Vertex) / sizeof(double), box);
}

void Triangulator::releaseWorkspace()
{
  std::vector<Vertex>().swap(vertices_);
  std::vector<std::uint32_t>().swap(vertexStamp_);
  grid_ = BackgroundGrid();
  cavity_.release();
}

void Triangulator::reserveForAll(std::size_t count)
{
  const double perVertex = double(mesh_.liveSlots()) / double(stats_.insertedPoints);
  mesh_.reserve(static_cast<std::size_t>(1.15 * perVertex * double(count)) + 64);
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
  // Ghost i sits on the face opposite v[i], in its outward order: the face normal then points away
  // from v[i], out of the hull.
  TetId ghost[4];
  for (int i = 0; i < 4; ++i)
  {
    ghost[i] = mesh_.allocate();
    const int* f = kFaceVertices[i];
    const VertId face[4] = {v[f[0]], v[f[1]], v[f[2]], kInfinite};
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
    vertices_[v[i]].tet = t;
    if (grid_.enabled())
      grid_.markInserted(point(v[i]), v[i]);
  }
  lastInserted_ = 3;
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

bool Triangulator::insert(VertId v)
{
  PhaseClock clock(v % kSampling == 0);
  const TetId base = locate(v);
  clock.lap(stats_.secondsLocate);
  digCavity(base, v);
  if (options_.tolerance > 0)
  {
    nearVertex_ = vertexWithin(options_.tolerance * options_.tolerance, v);
    if (nearVertex_ != kNoVertex)
    {
      undoCavity();
      return false;
    }
  }
  correctCavity(v);
  clock.lap(stats_.secondsCavity);
  fillCavity(v);
  clock.lap(stats_.secondsFill);
  if (grid_.enabled())
    grid_.markInserted(point(v), v);
  lastInserted_ = v;
  ++stats_.insertedPoints;
  return true;
}

} // namespace fd3
