// Finding the base: the tetrahedron that contains the new point (or a ghost tetrahedron whose hull
// face the point lies strictly beyond).
#include "Triangulator.h"

namespace fd3
{
namespace
{
// Layers of the onion searched before giving up on the grid; a point far from every inserted
// one (early BRIO rounds) starts from the last created tetrahedron instead.
constexpr int kMaxOnionLayers = 3;
} // namespace

TetId Triangulator::startTet(VertId v)
{
  TetId t = lastCreated_;
  if (grid_.enabled())
  {
    const VertId near = grid_.nearestInserted(point(v), kMaxOnionLayers);
    if (near != BackgroundGrid::kEmpty)
      t = vertexTet_[near];
  }
  return mesh_.isGhost(t) ? tetOf(mesh_.neighbor(t, 3)) : t;
}

// The paper's random walk: from the current tetrahedron, cross a face that separates it from the
// point, chosen at random among the separating ones (a random first face, then cyclic order).
// The randomness is what keeps the walk from cycling; it is seeded, so runs are reproducible.
TetId Triangulator::walk(TetId t, VertId v)
{
  const double* p = point(v);
  int entryFace = -1;
  std::size_t steps = 0;
  while (!mesh_.isGhost(t))
  {
    ++steps;
    VertId tv[4];
    mesh_.vertices(t, tv);
    const double* q[4] = {point(tv[0]), point(tv[1]), point(tv[2]), point(tv[3])};
    const int first = static_cast<int>(nextRandom() & 3u);
    int exit = -1;
    for (int k = 0; k < 4 && exit < 0; ++k)
    {
      const int f = (first + k) & 3;
      if (f == entryFace)
        continue;
      const double* saved = q[f];
      q[f] = p;
      if (predicates_.orient3d(q[0], q[1], q[2], q[3]) < 0)
        exit = f;
      q[f] = saved;
    }
    if (exit < 0)
      break;
    const FaceCode next = mesh_.neighbor(t, exit);
    t = tetOf(next);
    entryFace = faceOf(next);
  }
  stats_.walkSteps += steps;
  stats_.maxWalkSteps = std::max(stats_.maxWalkSteps, steps);
  return t;
}

TetId Triangulator::locate(VertId v)
{
  return walk(startTet(v), v);
}

} // namespace fd3
