// Periodic boxes through the filters: Fast Delaunay 3D's tetrahedra, placed to tile one period
// with image points, decided by the exact periodic validator; the periodic density; Fast
// Voronoi 3D's periodic cells, whose volumes fill the box and whose neighbours are the Delaunay
// tetrahedralization's edges across the box; the box from UseInputBounds and Bounds; bad input.
#include "PeriodicValidator.h"
#include "PointSets.h"
#include "VtkTestUtilities.h"
#include "vtkFastDelaunay3D.h"
#include "vtkFastVoronoi3D.h"

#include <gtest/gtest.h>

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Measures.h"
#include "fd3/Periodic.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace
{
using fd3test::Points;

/// Uniform points in [0, side)^3 with a "Tag" array (the point's id), some moved out of the box
/// by whole periods along x.
vtkSmartPointer<vtkPolyData> Cloud(std::size_t n, double side, std::uint64_t seed)
{
  Points p = fd3test::uniformCube(n, seed);
  for (double& x : p)
    x *= side;
  for (std::size_t i = 0; i < n; i += 11)
    p[3 * i] += (i % 2 ? 2 : -1) * side;
  auto cloud = fd3test::toPolyData(p);
  vtkNew<vtkDoubleArray> tag;
  tag->SetName("Tag");
  for (std::size_t i = 0; i < n; ++i)
    tag->InsertNextValue(double(i));
  cloud->GetPointData()->AddArray(tag);
  return cloud;
}

/// The periods (whole numbers) by which each output point of `grid` lies from the input point
/// that SourcePointId names.
std::vector<std::array<std::int32_t, 3>> Shifts(
  vtkUnstructuredGrid* grid, vtkPolyData* input, const double period[3])
{
  vtkDataArray* source = grid->GetPointData()->GetArray("SourcePointId");
  std::vector<std::array<std::int32_t, 3>> shifts(grid->GetNumberOfPoints());
  for (vtkIdType v = 0; v < grid->GetNumberOfPoints(); ++v)
  {
    const vtkIdType s = static_cast<vtkIdType>(source->GetTuple1(v));
    for (int a = 0; a < 3; ++a)
    {
      const double moved = grid->GetPoint(v)[a] - input->GetPoint(s)[a];
      shifts[v][a] = static_cast<std::int32_t>(std::lround(moved / period[a]));
      EXPECT_EQ(grid->GetPoint(v)[a], input->GetPoint(s)[a] + shifts[v][a] * period[a]);
    }
  }
  return shifts;
}

/// The output as the validator takes it: each vertex by its input point, with the offset from
/// that point's place in the box.
std::vector<fd3test::PeriodicTetrahedron> PeriodicTetrahedra(
  vtkUnstructuredGrid* grid, vtkPolyData* input, const fd3test::PeriodicDomain& box)
{
  double period[3];
  for (int a = 0; a < 3; ++a)
    period[a] = box.hi[a] - box.lo[a];
  const auto shifts = Shifts(grid, input, period);
  vtkDataArray* source = grid->GetPointData()->GetArray("SourcePointId");
  const std::vector<std::uint32_t> ids = fd3test::tetrahedra(grid);
  std::vector<fd3test::PeriodicTetrahedron> tets(ids.size() / 4);
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int i = 0; i < 4; ++i)
    {
      const vtkIdType v = ids[4 * t + i];
      const vtkIdType s = static_cast<vtkIdType>(source->GetTuple1(v));
      tets[t].ids[i] = static_cast<std::uint32_t>(s);
      for (int a = 0; a < 3; ++a)
      {
        // The input point wraps by `wraps` periods into the box; the vertex is `offset` away.
        const std::int32_t wraps = box.periodic[a]
          ? static_cast<std::int32_t>(std::floor((input->GetPoint(s)[a] - box.lo[a]) / period[a]))
          : 0;
        tets[t].offsets[i][a] = shifts[v][a] + wraps;
      }
    }
  return tets;
}

vtkNew<vtkFastDelaunay3D> PeriodicDelaunay(vtkPolyData* input, double side, bool z = true)
{
  vtkNew<vtkFastDelaunay3D> delaunay;
  delaunay->SetInputData(input);
  delaunay->SetPeriodic(1, 1, z);
  delaunay->UseInputBoundsOff();
  delaunay->SetBounds(0, side, 0, side, 0, side);
  return delaunay;
}

TEST(PeriodicFilter, DelaunayTetrahedraTileOnePeriodAndAreValid)
{
  auto cloud = Cloud(1500, 2.0, 31);
  auto delaunay = PeriodicDelaunay(cloud, 2.0);
  delaunay->ComputeVolumeOn();
  delaunay->Update();
  vtkUnstructuredGrid* out = delaunay->GetOutput();
  EXPECT_GT(out->GetNumberOfPoints(), 1500);
  EXPECT_EQ(out->GetNumberOfCells(), delaunay->GetNumberOfTetrahedra());
  EXPECT_NEAR(fd3test::sum(out->GetCellData()->GetArray("Volume")), 8.0, 8.0 * 1e-12);
  // Every output point, image or not, has its input point's data.
  vtkDataArray* tag = out->GetPointData()->GetArray("Tag");
  vtkDataArray* source = out->GetPointData()->GetArray("SourcePointId");
  ASSERT_TRUE(tag && source);
  for (vtkIdType v = 0; v < out->GetNumberOfPoints(); ++v)
  {
    EXPECT_EQ(tag->GetTuple1(v), source->GetTuple1(v));
    if (v < 1500)
      EXPECT_EQ(source->GetTuple1(v), v);
  }
  fd3test::PeriodicDomain box;
  std::fill(box.hi, box.hi + 3, 2.0);
  const Points xyz = fd3test::coordinates(cloud);
  const auto report =
    fd3test::checkPeriodicTriangulation(xyz.data(), 1500, box, PeriodicTetrahedra(out, cloud, box));
  EXPECT_TRUE(report.valid()) << report.summary();
}

TEST(PeriodicFilter, SlabPeriodicInXAndY)
{
  auto cloud = Cloud(800, 1.0, 32);
  auto delaunay = PeriodicDelaunay(cloud, 1.0, false);
  delaunay->Update();
  fd3test::PeriodicDomain box;
  box.periodic[2] = false;
  const Points xyz = fd3test::coordinates(cloud);
  const auto report = fd3test::checkPeriodicTriangulation(
    xyz.data(), 800, box, PeriodicTetrahedra(delaunay->GetOutput(), cloud, box));
  EXPECT_TRUE(report.valid()) << report.summary();
}

// The DTFE of a periodic box has no boundary: the linear field through the points' densities
// integrates over the placed tetrahedra to the number of points.
TEST(PeriodicFilter, DensityIntegratesToThePoints)
{
  auto cloud = Cloud(2000, 1.0, 33);
  auto delaunay = PeriodicDelaunay(cloud, 1.0);
  delaunay->ComputeDensityOn();
  delaunay->ComputeVolumeOn();
  delaunay->Update();
  vtkUnstructuredGrid* out = delaunay->GetOutput();
  vtkDataArray* density = out->GetPointData()->GetArray("Density");
  vtkDataArray* volume = out->GetCellData()->GetArray("Volume");
  const std::vector<std::uint32_t> ids = fd3test::tetrahedra(out);
  double integral = 0;
  for (std::size_t t = 0; t < ids.size() / 4; ++t)
  {
    double mean = 0;
    for (int i = 0; i < 4; ++i)
      mean += density->GetTuple1(ids[4 * t + i]) / 4;
    integral += mean * volume->GetTuple1(static_cast<vtkIdType>(t));
  }
  EXPECT_NEAR(integral, 2000.0, 2000.0 * 1e-9);
}

// Each point's periodic cell has a face for each of its Delaunay edges, across the box's sides
// too: NumberOfNeighbors counts the distinct edges (by the other point and its period) of the
// point in Fast Delaunay 3D's periodic tetrahedra.
TEST(PeriodicFilter, VoronoiCellsFillTheBoxWithTheDelaunayNeighbours)
{
  auto cloud = Cloud(1200, 1.0, 34);
  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(cloud);
  voronoi->SetPeriodic(1, 1, 1);
  voronoi->UseInputBoundsOff();
  voronoi->SetBounds(0, 1, 0, 1, 0, 1);
  voronoi->Update();
  vtkUnstructuredGrid* cells = voronoi->GetOutput();
  ASSERT_EQ(cells->GetNumberOfCells(), 1200);
  EXPECT_NEAR(fd3test::sum(cells->GetCellData()->GetArray("Volume")), 1.0, 1e-12);

  auto delaunay = PeriodicDelaunay(cloud, 1.0);
  delaunay->Update();
  vtkUnstructuredGrid* tets = delaunay->GetOutput();
  const double period[3] = {1, 1, 1};
  const auto shifts = Shifts(tets, cloud, period);
  vtkDataArray* source = tets->GetPointData()->GetArray("SourcePointId");
  std::vector<std::set<std::array<std::int64_t, 4>>> edges(1200);
  const std::vector<std::uint32_t> ids = fd3test::tetrahedra(tets);
  for (std::size_t t = 0; t < ids.size() / 4; ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j)
        {
          const vtkIdType a = ids[4 * t + i], b = ids[4 * t + j];
          edges[static_cast<std::size_t>(source->GetTuple1(a))].insert(
            {static_cast<std::int64_t>(source->GetTuple1(b)), shifts[b][0] - shifts[a][0],
              shifts[b][1] - shifts[a][1], shifts[b][2] - shifts[a][2]});
        }
  vtkDataArray* generator = cells->GetCellData()->GetArray("GeneratorId");
  vtkDataArray* neighbours = cells->GetCellData()->GetArray("NumberOfNeighbors");
  for (vtkIdType c = 0; c < 1200; ++c)
    EXPECT_EQ(neighbours->GetTuple1(c),
      double(edges[static_cast<std::size_t>(generator->GetTuple1(c))].size()));
}

TEST(PeriodicFilter, UseInputBoundsChoosesTheBox)
{
  auto cloud = Cloud(500, 1.0, 35);
  vtkNew<vtkFastDelaunay3D> delaunay;
  EXPECT_EQ(delaunay->GetUseInputBounds(), 1);
  delaunay->SetInputData(cloud);
  delaunay->SetPeriodic(1, 1, 1);
  delaunay->SetBounds(0, 5, 0, 5, 0, 5); // not used: UseInputBounds is on
  delaunay->ComputeVolumeOn();
  delaunay->Update();
  double bounds[6];
  cloud->GetBounds(bounds);
  const double box = (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]) * (bounds[5] - bounds[4]);
  EXPECT_NEAR(
    fd3test::sum(delaunay->GetOutput()->GetCellData()->GetArray("Volume")), box, 1e-12 * box);

  // No box: a warning, and the input's bounds.
  delaunay->UseInputBoundsOff();
  delaunay->SetBounds(0, -1, 0, 1, 0, std::nan(""));
  vtkNew<vtkTest::ErrorObserver> observer;
  delaunay->AddObserver(vtkCommand::WarningEvent, observer);
  delaunay->Update();
  EXPECT_NE(observer->GetWarningMessage().find("is no box"), std::string::npos)
    << observer->GetWarningMessage();
  EXPECT_NEAR(
    fd3test::sum(delaunay->GetOutput()->GetCellData()->GetArray("Volume")), box, 1e-12 * box);
}

TEST(PeriodicFilter, BadInputGivesAMessageAndTheCloud)
{
  // Coplanar points and the input's bounds: no period along z.
  Points flat = fd3test::uniformCube(100, 36);
  for (std::size_t i = 2; i < flat.size(); i += 3)
    flat[i] = 0.5;
  vtkNew<vtkFastDelaunay3D> delaunay;
  delaunay->SetInputData(fd3test::toPolyData(flat));
  delaunay->SetPeriodic(1, 1, 1);
  vtkNew<vtkTest::ErrorObserver> observer;
  delaunay->AddObserver(vtkCommand::WarningEvent, observer);
  delaunay->AddObserver(vtkCommand::ErrorEvent, observer);
  delaunay->Update();
  EXPECT_NE(observer->GetWarningMessage().find("no period"), std::string::npos)
    << observer->GetWarningMessage();
  EXPECT_EQ(delaunay->GetOutput()->GetNumberOfPoints(), 100);
  EXPECT_EQ(delaunay->GetOutput()->GetNumberOfCells(), 0);

  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(fd3test::toPolyData(flat));
  voronoi->SetPeriodic(0, 0, 1);
  voronoi->AddObserver(vtkCommand::ErrorEvent, observer);
  voronoi->Update();
  EXPECT_NE(observer->GetErrorMessage().find("no period"), std::string::npos)
    << observer->GetErrorMessage();
  EXPECT_EQ(voronoi->GetOutput()->GetNumberOfCells(), 0);

  // Weights of two components: no weights to read.
  auto cloud = Cloud(200, 1.0, 37);
  vtkNew<vtkDoubleArray> pairs;
  pairs->SetName("Pairs");
  pairs->SetNumberOfComponents(2);
  pairs->SetNumberOfTuples(200);
  pairs->Fill(0.01);
  cloud->GetPointData()->AddArray(pairs);
  auto weighted = PeriodicDelaunay(cloud, 1.0);
  weighted->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Pairs");
  weighted->AddObserver(vtkCommand::ErrorEvent, observer);
  weighted->Update();
  EXPECT_NE(observer->GetErrorMessage().find("weights"), std::string::npos)
    << observer->GetErrorMessage();
  EXPECT_EQ(weighted->GetOutput()->GetNumberOfPoints(), 200);
  EXPECT_EQ(weighted->GetOutput()->GetNumberOfCells(), 0);
}

// Radii in a periodic box: the periodic regular tetrahedralization, decided by the exact
// validator with Core's hidden points, which no cell uses; the power cells fill the box, a hidden
// point's empty; the weighted alpha shape is Core's.
TEST(PeriodicFilter, RadiiGiveThePeriodicRegularTetrahedralizationAndPowerCells)
{
  const std::size_t n = 1000;
  auto cloud = Cloud(n, 1.0, 39);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("Radius");
  std::vector<double> weights(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double r = 0.07 * double((i * 7919) % n) / double(n);
    radius->InsertNextValue(r);
    weights[i] = r * r;
  }
  cloud->GetPointData()->AddArray(radius);
  const Points xyz = fd3test::coordinates(cloud);
  fd3::PeriodicBox unit;
  const fd3::PeriodicTriangulation core =
    fd3::triangulatePeriodic(xyz.data(), weights.data(), n, unit);
  ASSERT_EQ(core.status, fd3::Status::Ok);
  ASSERT_FALSE(core.hidden.empty());

  auto delaunay = PeriodicDelaunay(cloud, 1.0);
  delaunay->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
  delaunay->ComputeVolumeOn();
  delaunay->Update();
  vtkUnstructuredGrid* out = delaunay->GetOutput();
  EXPECT_EQ(out->GetNumberOfCells(), vtkIdType(core.numberOfTetrahedra()));
  EXPECT_EQ(delaunay->GetNumberOfHiddenPoints(), vtkIdType(core.hidden.size()));
  EXPECT_NEAR(fd3test::sum(out->GetCellData()->GetArray("Volume")), 1.0, 1e-12);
  fd3test::PeriodicDomain box;
  fd3test::ValidityOptions check;
  check.weights = weights.data();
  check.hidden = core.hidden;
  const auto report = fd3test::checkPeriodicTriangulation(
    xyz.data(), n, box, PeriodicTetrahedra(out, cloud, box), check);
  EXPECT_TRUE(report.valid()) << report.summary();

  delaunay->SetAlpha(0.05);
  delaunay->Update();
  const fd3::PeriodicPlacement placed = fd3::placePeriodic(xyz.data(), n, core, unit);
  const fd3::AlphaComplex shape =
    fd3::alphaComplex(xyz.data(), weights.data(), n, placed, core.hidden, 0.05);
  EXPECT_EQ(delaunay->GetOutput()->GetNumberOfCells(),
    vtkIdType(shape.tetrahedra.size() + shape.triangles.size() / 3 + shape.lines.size() / 2 +
      shape.vertices.size()));

  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(cloud);
  voronoi->SetPeriodic(1, 1, 1);
  voronoi->UseInputBoundsOff();
  voronoi->SetBounds(0, 1, 0, 1, 0, 1);
  voronoi->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
  voronoi->Update();
  vtkUnstructuredGrid* cells = voronoi->GetOutput();
  EXPECT_EQ(voronoi->GetNumberOfHiddenPoints(), vtkIdType(core.hidden.size()));
  vtkDataArray* volume = cells->GetCellData()->GetArray("Volume");
  EXPECT_NEAR(fd3test::sum(volume), 1.0, 1e-12);
  vtkDataArray* generator = cells->GetCellData()->GetArray("GeneratorId");
  for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
    if (std::binary_search(core.hidden.begin(), core.hidden.end(),
          static_cast<std::uint32_t>(generator->GetTuple1(c))))
      EXPECT_EQ(volume->GetTuple1(c), 0.0);
}

// Alpha in a periodic box: the periodic alpha shape, every simplex within Alpha, the tetrahedra
// those of the whole periodic tetrahedralization within it, lower simplices too.
TEST(PeriodicFilter, AlphaShapeIsPeriodic)
{
  auto cloud = Cloud(1000, 1.0, 38);
  auto delaunay = PeriodicDelaunay(cloud, 1.0);
  delaunay->ComputeCircumradiusOn();
  delaunay->Update();
  vtkDataArray* all = delaunay->GetOutput()->GetCellData()->GetArray("Circumradius");
  vtkIdType small = 0;
  for (vtkIdType c = 0; c < all->GetNumberOfTuples(); ++c)
    small += all->GetTuple1(c) <= 0.06;
  delaunay->SetAlpha(0.06);
  vtkNew<vtkTest::ErrorObserver> observer;
  delaunay->AddObserver(vtkCommand::WarningEvent, observer);
  delaunay->Update();
  EXPECT_FALSE(observer->GetWarning()) << observer->GetWarningMessage();
  vtkUnstructuredGrid* shape = delaunay->GetOutput();
  vtkDataArray* radius = shape->GetCellData()->GetArray("Circumradius");
  std::map<int, vtkIdType> types;
  for (vtkIdType c = 0; c < shape->GetNumberOfCells(); ++c)
  {
    ++types[shape->GetCellType(c)];
    EXPECT_LE(radius->GetTuple1(c), 0.06);
  }
  EXPECT_EQ(types[VTK_TETRA], small);
  EXPECT_GT(types[VTK_TRIANGLE], 0);
  EXPECT_GT(types[VTK_LINE], 0);
}
} // namespace
