// The kernel's own check (Options::checkMesh, on in debug builds) finds what is broken: a mesh is
// built and checked clean, then broken one invariant at a time, each time in a fresh mesh.
#include "PointSets.h"
#include "insertion/Triangulator.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace
{
/// The mesh of `p` (points in the unit cube, the first four affinely independent), mapped into
/// [-1, 1] as the kernel's frame maps them.
std::unique_ptr<fd3::Triangulator> meshOf(const fd3test::Points& p)
{
  fd3::VertexArray vertices(p.size() / 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    for (int a = 0; a < 3; ++a)
      vertices[i].xyz[a] = 2 * p[3 * i + a] - 1;
    vertices[i].tet = fd3::kNoTet;
    vertices[i].point = static_cast<std::uint32_t>(i);
  }
  fd3::Bounds box;
  for (int a = 0; a < 3; ++a)
  {
    box.lo[a] = -1;
    box.hi[a] = 1;
  }
  static fd3::ThreadTeam oneThread(1);
  auto mesh =
    std::make_unique<fd3::Triangulator>(std::move(vertices), box, fd3::Options(), oneThread, false);
  EXPECT_TRUE(mesh->insertAll({0}, nullptr));
  return mesh;
}

/// The first finite tetrahedron from slot `from` on.
fd3::TetId finiteTet(const fd3::TetMesh& tets, fd3::TetId from = 0)
{
  fd3::TetId t = from;
  while (tets.isDead(t) || tets.isGhost(t))
    ++t;
  return t;
}

bool says(const std::string& report, const std::string& what)
{
  return report.find(what) != std::string::npos;
}

TEST(MeshCheck, FindsEachBrokenInvariant)
{
  const fd3test::Points p = fd3test::uniformCube(2000, 7);
  EXPECT_EQ(meshOf(p)->checkMesh(), "");

  // Writing into a live mesh is what the check guards against; the casts break it on purpose.
  {
    auto mesh = meshOf(p);
    auto& tets = const_cast<fd3::TetMesh&>(mesh->tetrahedra());
    // A tetrahedron tested and kept whose flag was not cleared (a live one flagged kInCavity reads
    // as dead: freed, but in no free list, below).
    tets.setFlags(finiteTet(tets, 100), fd3::kNotInCavity);
    EXPECT_TRUE(says(mesh->checkMesh(), "keeps cavity flags")) << mesh->checkMesh();
  }
  {
    auto mesh = meshOf(p);
    auto& tets = const_cast<fd3::TetMesh&>(mesh->tetrahedra());
    const fd3::TetId t = finiteTet(tets, 100);
    tets.setNeighbor(fd3::faceCode(t, 0), tets.neighbor(t, 1));
    EXPECT_TRUE(says(mesh->checkMesh(), "adjacency: tet")) << mesh->checkMesh();
  }
  {
    auto mesh = meshOf(p);
    auto& tets = const_cast<fd3::TetMesh&>(mesh->tetrahedra());
    tets.setFlags(finiteTet(tets, 100), fd3::kDead); // freed, but in no free list
    const std::string report = mesh->checkMesh();
    EXPECT_TRUE(says(report, "is not listed")) << report;
    EXPECT_TRUE(says(report, "not linked both ways")) << report; // its neighbours still point to it
  }
  {
    // A vertex moved: the spheres of its neighbours' tetrahedra hold it.
    auto mesh = meshOf(p);
    auto& vertices = const_cast<fd3::VertexArray&>(mesh->vertices());
    vertices[1000].xyz[0] += 0.5;
    const std::string report = mesh->checkMesh();
    EXPECT_TRUE(says(report, "Delaunay: tet")) << report;
  }
  {
    auto mesh = meshOf(p);
    auto& vertices = const_cast<fd3::VertexArray&>(mesh->vertices());
    vertices[1500].tet = fd3::kNoTet;
    EXPECT_TRUE(says(mesh->checkMesh(), "vertex tet: vertex 1500")) << mesh->checkMesh();
  }
}
} // namespace
