// Drop-in parity with vtkDelaunay3D: same defaults, same tetrahedra and alpha shapes where both
// are well defined, and the extra properties' contracts.
#include "VtkTestUtilities.h"
#include "fd3/Delaunay.h"
#include "fd3/Distributed.h"
#include "vtkFastDelaunay3D.h"

#include <gtest/gtest.h>

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDelaunay3D.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkTetra.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <map>
#include <set>
#include <vector>

namespace
{
using Cell = std::vector<vtkIdType>; // sorted point ids
using fd3test::toPolyData;

/// Cells by type, each as its sorted point ids.
std::map<int, std::set<Cell>> CellsByType(vtkUnstructuredGrid* grid)
{
  std::map<int, std::set<Cell>> cells;
  auto it = vtk::TakeSmartPointer(grid->GetCells()->NewIterator());
  vtkIdType c = 0;
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++c)
  {
    vtkIdType size;
    const vtkIdType* ids;
    it->GetCurrentCell(size, ids);
    Cell cell(ids, ids + size);
    std::sort(cell.begin(), cell.end());
    cells[grid->GetCellType(c)].insert(cell);
  }
  return cells;
}

/// Points on the convex hull, from the exact tetrahedralization: faces used by one tetrahedron.
std::set<vtkIdType> HullPoints(vtkUnstructuredGrid* tets)
{
  std::map<Cell, int> faces;
  auto cells = CellsByType(tets);
  for (const Cell& t : cells[VTK_TETRA])
    for (int skip = 0; skip < 4; ++skip)
    {
      Cell f;
      for (int k = 0; k < 4; ++k)
        if (k != skip)
          f.push_back(t[k]);
      ++faces[f];
    }
  std::set<vtkIdType> hull;
  for (const auto& [f, uses] : faces)
    if (uses == 1)
      hull.insert(f.begin(), f.end());
  return hull;
}

std::set<Cell> AwayFrom(const std::set<Cell>& cells, const std::set<vtkIdType>& points)
{
  std::set<Cell> kept;
  for (const Cell& c : cells)
    if (std::none_of(c.begin(), c.end(), [&](vtkIdType id) { return points.count(id) > 0; }))
      kept.insert(c);
  return kept;
}

TEST(Parity, DefaultsAreVtkDelaunay3Ds)
{
  vtkNew<vtkDelaunay3D> theirs;
  vtkNew<vtkFastDelaunay3D> ours;
  EXPECT_EQ(ours->GetAlpha(), theirs->GetAlpha());
  EXPECT_EQ(ours->GetAlphaTets(), theirs->GetAlphaTets());
  EXPECT_EQ(ours->GetAlphaTris(), theirs->GetAlphaTris());
  EXPECT_EQ(ours->GetAlphaLines(), theirs->GetAlphaLines());
  EXPECT_EQ(ours->GetAlphaVerts(), theirs->GetAlphaVerts());
  // The one deliberate difference: vtkDelaunay3D 9.2 shows 0.001 but never applies it (it keeps
  // every point); applied, 0.001 would drop most of a dense cloud, so ours is 0.
  EXPECT_EQ(theirs->GetTolerance(), 0.001);
  EXPECT_EQ(ours->GetTolerance(), 0.0);
  EXPECT_EQ(ours->GetOffset(), theirs->GetOffset());
  EXPECT_EQ(ours->GetBoundingTriangulation(), theirs->GetBoundingTriangulation());
  EXPECT_EQ(ours->GetOutputPointsPrecision(), theirs->GetOutputPointsPrecision());
  ours->SetOffset(1.0); // same clamping ranges
  theirs->SetOffset(1.0);
  EXPECT_EQ(ours->GetOffset(), theirs->GetOffset());
  ours->SetTolerance(2.0);
  theirs->SetTolerance(2.0);
  EXPECT_EQ(ours->GetTolerance(), theirs->GetTolerance());
}

// In general position the Delaunay tetrahedralization is unique; vtkDelaunay3D's bounding
// octahedron only changes tetrahedra whose circumsphere reaches it, near the hull.
TEST(Parity, SameTetrahedraAwayFromTheHull)
{
  auto cloud = toPolyData(fd3test::uniformBall(3000, 21));
  vtkNew<vtkDelaunay3D> theirs;
  theirs->SetInputData(cloud);
  theirs->Update();
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  ours->Update();
  const std::set<vtkIdType> hull = HullPoints(ours->GetOutput());
  const auto a = AwayFrom(CellsByType(theirs->GetOutput())[VTK_TETRA], hull);
  const auto b = AwayFrom(CellsByType(ours->GetOutput())[VTK_TETRA], hull);
  EXPECT_GT(b.size(), 15000u);
  EXPECT_EQ(a, b);
}

TEST(Parity, SameAlphaShapes)
{
  auto cloud = toPolyData(fd3test::uniformBall(3000, 22));
  vtkNew<vtkFastDelaunay3D> full;
  full->SetInputData(cloud);
  full->Update();
  const std::set<vtkIdType> hull = HullPoints(full->GetOutput());
  for (double alpha : {0.05, 0.08, 0.12})
  {
    vtkNew<vtkDelaunay3D> theirs;
    theirs->SetInputData(cloud);
    theirs->SetAlpha(alpha);
    theirs->Update();
    vtkNew<vtkFastDelaunay3D> ours;
    ours->SetInputData(cloud);
    ours->SetAlpha(alpha);
    ours->SetAlphaLines(1); // vtkDelaunay3D's defaults: every kind on
    ours->SetAlphaVerts(1);
    ours->Update();
    auto a = CellsByType(theirs->GetOutput());
    auto b = CellsByType(ours->GetOutput());
    // Tetrahedra of radius <= alpha never reach vtkDelaunay3D's bounding octahedron: identical
    // everywhere. Lower-dimensional cells on the hull are not compared: vtkDelaunay3D reports a
    // hull face only when the bounding tetrahedron behind it has the larger cell id.
    EXPECT_EQ(a[VTK_TETRA], b[VTK_TETRA]) << "alpha " << alpha;
    EXPECT_GT(b[VTK_TETRA].size(), 0u);
    for (int type : {VTK_TRIANGLE, VTK_LINE, VTK_VERTEX})
    {
      const auto inA = AwayFrom(a[type], hull), inB = AwayFrom(b[type], hull);
      EXPECT_EQ(inA.size(), inB.size()) << "alpha " << alpha << " cell type " << type;
      EXPECT_EQ(inA, inB) << "alpha " << alpha << " cell type " << type;
    }
    EXPECT_GT(b[VTK_TRIANGLE].size(), 0u);
    // Cell order as vtkDelaunay3D: lower dimensions first, tetrahedra last.
    const vtkIdType last = ours->GetOutput()->GetNumberOfCells() - 1;
    EXPECT_EQ(ours->GetOutput()->GetCellType(last), VTK_TETRA);
  }
}

TEST(Parity, BoundingTriangulationHoldsTheOctahedron)
{
  const fd3test::Points p = fd3test::uniformBall(500, 23);
  auto cloud = toPolyData(p);
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  ours->SetBoundingTriangulation(1);
  ours->Update();
  vtkUnstructuredGrid* out = ours->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 506);
  EXPECT_EQ(out->GetPointData()->GetNumberOfArrays(), 0);
  const auto report = fd3test::checkOutput(out); // every point used: the 6 bounding ones too
  EXPECT_TRUE(report.valid()) << report.summary();
  EXPECT_EQ(report.hullFaces, 8u); // the octahedron
  const std::set<vtkIdType> hull = HullPoints(out);
  EXPECT_EQ(hull, (std::set<vtkIdType>{500, 501, 502, 503, 504, 505}));
}

TEST(Parity, OutputPointsPrecision)
{
  auto cloud = toPolyData(fd3test::uniformCube(200, 24), VTK_FLOAT);
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  ours->Update();
  EXPECT_EQ(ours->GetOutput()->GetPoints()->GetDataType(), VTK_FLOAT);
  EXPECT_EQ(ours->GetOutput()->GetPoints(), cloud->GetPoints());
  ours->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  ours->Update();
  EXPECT_EQ(ours->GetOutput()->GetPoints()->GetDataType(), VTK_DOUBLE);
  ours->SetOutputPointsPrecision(vtkAlgorithm::SINGLE_PRECISION);
  ours->Update();
  EXPECT_EQ(ours->GetOutput()->GetPoints()->GetDataType(), VTK_FLOAT);
}

TEST(Parity, ToleranceSkipsClosePointsOnly)
{
  fd3test::Points p = fd3test::uniformCube(1000, 25);
  p.insert(p.end(), {p[0] + 1e-6, p[1], p[2]}); // within 0.001 * diagonal of point 0
  auto cloud = toPolyData(p);
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  ours->SetTolerance(1e-5);
  ours->Update();
  EXPECT_EQ(ours->GetNumberOfSkippedPoints(), 1);
  EXPECT_EQ(ours->GetNumberOfInsertedPoints(), 1000);
  ours->SetTolerance(0);
  ours->Update();
  EXPECT_EQ(ours->GetNumberOfSkippedPoints(), 0);
  EXPECT_EQ(ours->GetNumberOfInsertedPoints(), 1001);
}

TEST(Parity, OptionalArraysAndStatistics)
{
  auto cloud = toPolyData(fd3test::uniformCube(2000, 26));
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  ours->Update();
  EXPECT_EQ(ours->GetOutput()->GetCellData()->GetNumberOfArrays(), 0); // off by default
  EXPECT_EQ(ours->GetOutput()->GetFieldData()->GetNumberOfArrays(), 0);
  ours->ComputeCircumradiusOn();
  ours->ComputeVolumeOn();
  ours->ComputeRadiusEdgeRatioOn();
  ours->ComputeStatisticsOn();
  ours->Update();
  vtkUnstructuredGrid* out = ours->GetOutput();
  vtkDataArray* volume = out->GetCellData()->GetArray("Volume");
  vtkDataArray* radius = out->GetCellData()->GetArray("Circumradius");
  vtkDataArray* ratio = out->GetCellData()->GetArray("RadiusEdgeRatio");
  ASSERT_TRUE(volume && radius && ratio);
  double total = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    EXPECT_GT(volume->GetTuple1(c), 0);
    EXPECT_GT(radius->GetTuple1(c), 0);
    EXPECT_GE(ratio->GetTuple1(c), std::sqrt(3.0 / 8.0) - 1e-9); // the regular one is the best
    total += volume->GetTuple1(c);
  }
  double bounds[6];
  cloud->GetBounds(bounds);
  EXPECT_LT(total, (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]) * (bounds[5] - bounds[4]));
  EXPECT_GT(total, 0.95); // the hull of 2000 uniform points fills most of the unit cube
  vtkFieldData* fields = out->GetFieldData();
  ASSERT_NE(fields->GetArray("NumberOfTetrahedra"), nullptr);
  EXPECT_EQ(fields->GetArray("NumberOfTetrahedra")->GetTuple1(0), out->GetNumberOfCells());
  EXPECT_EQ(fields->GetArray("NumberOfInsertedPoints")->GetTuple1(0), 2000);
  auto figure = [fields](const char* name) {
    vtkDataArray* array = fields->GetArray(name);
    EXPECT_NE(array, nullptr) << name;
    return array ? array->GetTuple1(0) : -1.0;
  };
  EXPECT_GT(figure("MeanWalkLength"), 0);
  EXPECT_GE(figure("MaxWalkLength"), figure("MeanWalkLength"));
  EXPECT_EQ(figure("MaxWalkLength"), ours->GetMaxWalkLength());
  // Each insertion deletes at least the tetrahedron holding the point; about 20 on uniform points.
  EXPECT_GT(figure("MeanCavitySize"), 5);
  EXPECT_LT(figure("MeanCavitySize"), 60);
  const double kernel = figure("KernelSeconds");
  EXPECT_GT(kernel, 0);
  double phases = 0;
  for (const char* phase : {"SortSeconds", "LocateSeconds", "CavitySeconds", "FillSeconds"})
  {
    EXPECT_GE(figure(phase), 0) << phase;
    phases += figure(phase);
  }
  EXPECT_GT(phases, 0);
  EXPECT_GT(figure("OutputSeconds"), 0);
}

// What VTK's TestDelaunay3D asks: the output points' type follows OutputPointsPrecision on float
// and double input given as an unstructured grid with cells of its own; an empty input gives no
// points object at all (nothing of the wrong precision), with a warning and no error.
TEST(Parity, PointTypesAsVtkDelaunay3DsOnEveryInputAndNoneWhenEmpty)
{
  struct Case
  {
    int input, precision, expected;
  };
  const Case cases[] = {{VTK_FLOAT, vtkAlgorithm::DEFAULT_PRECISION, VTK_FLOAT},
    {VTK_DOUBLE, vtkAlgorithm::DEFAULT_PRECISION, VTK_DOUBLE},
    {VTK_FLOAT, vtkAlgorithm::SINGLE_PRECISION, VTK_FLOAT},
    {VTK_DOUBLE, vtkAlgorithm::SINGLE_PRECISION, VTK_FLOAT},
    {VTK_FLOAT, vtkAlgorithm::DOUBLE_PRECISION, VTK_DOUBLE},
    {VTK_DOUBLE, vtkAlgorithm::DOUBLE_PRECISION, VTK_DOUBLE},
    {VTK_DOUBLE, 7, VTK_FLOAT}}; // a value that is no precision
  for (const Case& c : cases)
  {
    vtkNew<vtkPoints> points;
    points->SetDataType(c.input);
    for (const auto& x :
      {std::array<double, 3>{0.1, 0.2, 0.3}, {0.9, 0.1, 0.2}, {0.3, 0.8, 0.1}, {0.4, 0.4, 0.9}})
      points->InsertNextPoint(x.data());
    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(points);
    const vtkIdType ids[4] = {0, 1, 2, 3};
    grid->InsertNextCell(VTK_VERTEX, 4, ids); // the input's cells play no part
    vtkNew<vtkFastDelaunay3D> ours;
    vtkNew<vtkDelaunay3D> theirs;
    ours->SetOutputPointsPrecision(c.precision);
    theirs->SetOutputPointsPrecision(c.precision);
    for (vtkUnstructuredGridAlgorithm* filter : {static_cast<vtkUnstructuredGridAlgorithm*>(ours),
           static_cast<vtkUnstructuredGridAlgorithm*>(theirs)})
    {
      filter->SetInputData(grid);
      filter->Update();
    }
    ASSERT_NE(ours->GetOutput()->GetPoints(), nullptr);
    EXPECT_EQ(ours->GetOutput()->GetPoints()->GetDataType(), c.expected);
    EXPECT_EQ(theirs->GetOutput()->GetPoints()->GetDataType(), c.expected);
    EXPECT_EQ(ours->GetOutput()->GetNumberOfCells(), 1);
  }
  vtkNew<vtkUnstructuredGrid> empty;
  empty->SetPoints(vtkNew<vtkPoints>()); // float, no points
  vtkNew<vtkFastDelaunay3D> ours;
  vtkNew<vtkTest::ErrorObserver> observer;
  ours->AddObserver(vtkCommand::WarningEvent, observer);
  ours->AddObserver(vtkCommand::ErrorEvent, observer);
  ours->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  ours->SetInputData(empty);
  ours->Update();
  EXPECT_EQ(ours->GetOutput()->GetPoints(), nullptr);
  EXPECT_EQ(ours->GetOutput()->GetNumberOfCells(), 0);
  EXPECT_EQ(observer->CheckWarningMessage("Cannot triangulate; no input points"), 0);
  EXPECT_FALSE(observer->GetError());
}

// What VTK's Delaunay3D.py draws: 25 random points, Tolerance 0.01, Alpha 0.2 (no tetrahedron is
// that small): the same triangles, lines and vertices as vtkDelaunay3D's away from the hull, where
// vtkDelaunay3D reports a hull face only when its bounding tetrahedron's id is the larger.
TEST(Parity, SmallRandomAlphaShape)
{
  vtkMath::RandomSeed(6);
  fd3test::Points p;
  for (int i = 0; i < 75; ++i)
    p.push_back(vtkMath::Random(0, 1));
  auto cloud = toPolyData(p);
  vtkNew<vtkDelaunay3D> theirs;
  vtkNew<vtkFastDelaunay3D> ours;
  for (vtkUnstructuredGridAlgorithm* filter : {static_cast<vtkUnstructuredGridAlgorithm*>(theirs),
         static_cast<vtkUnstructuredGridAlgorithm*>(ours)})
    filter->SetInputData(cloud);
  theirs->SetTolerance(0.01);
  theirs->SetAlpha(0.2);
  ours->SetTolerance(0.01);
  ours->SetAlpha(0.2);
  theirs->Update();
  ours->Update();
  auto a = CellsByType(theirs->GetOutput());
  auto b = CellsByType(ours->GetOutput());
  EXPECT_TRUE(b[VTK_TETRA].empty());
  EXPECT_EQ(a[VTK_VERTEX], b[VTK_VERTEX]); // points on no triangle or line
  vtkNew<vtkFastDelaunay3D> whole;
  whole->SetInputData(cloud);
  whole->Update();
  const std::set<vtkIdType> hull = HullPoints(whole->GetOutput());
  for (int type : {VTK_TRIANGLE, VTK_LINE})
  {
    EXPECT_EQ(AwayFrom(a[type], hull), AwayFrom(b[type], hull)) << "cell type " << type;
    EXPECT_FALSE(b[type].empty()) << "cell type " << type;
  }
}

// What VTK's Delaunay3DAlphaTest.py draws: boxes of cospherical corners (every insphere test of a
// box's corners is a tie), Alpha 2.8, AlphaLines off. The ties may be broken otherwise than by
// vtkDelaunay3D, so the cells are checked against the alpha shape's definition: tetrahedra of
// circumradius at most Alpha from the exact tetrahedralization, triangles on none of them, no
// lines, and every point on some cell.
TEST(Parity, DegenerateBoxesAlphaShape)
{
  const fd3test::Points p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1,
    5, 0, 0, 5, 1, 0, 10, 0, 0, 11, 0, 0, 10, 1, 0, 11, 1, 0, 10, 0, 1, 11, 0, 1, 10, 1, 1, 11, 1,
    1, 5, 0, 1, 5, 1, 1};
  auto cloud = toPolyData(p);
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  ours->SetTolerance(0.01);
  ours->SetAlpha(2.8);
  ours->AlphaTetsOn();
  ours->AlphaTrisOn();
  ours->AlphaLinesOff();
  ours->AlphaVertsOn();
  ours->Update();
  auto cells = CellsByType(ours->GetOutput());
  EXPECT_TRUE(cells[VTK_LINE].empty());
  ASSERT_FALSE(cells[VTK_TETRA].empty());
  vtkNew<vtkFastDelaunay3D> whole;
  whole->SetInputData(cloud);
  whole->Update();
  EXPECT_TRUE(fd3test::checkOutput(whole->GetOutput()).valid());
  auto all = CellsByType(whole->GetOutput());
  std::set<Cell> facesOfKept;
  std::set<vtkIdType> used;
  for (const Cell& t : cells[VTK_TETRA])
  {
    EXPECT_TRUE(all[VTK_TETRA].count(t)) << "a tetrahedron of the tetrahedralization";
    double x[4][3];
    for (int k = 0; k < 4; ++k)
      cloud->GetPoint(t[k], x[k]);
    double centre[3];
    EXPECT_LE(std::sqrt(vtkTetra::Circumsphere(x[0], x[1], x[2], x[3], centre)), 2.8 + 1e-12);
    for (int skip = 0; skip < 4; ++skip)
    {
      Cell f;
      for (int k = 0; k < 4; ++k)
        if (k != skip)
          f.push_back(t[k]);
      facesOfKept.insert(f);
    }
    used.insert(t.begin(), t.end());
  }
  for (const Cell& f : cells[VTK_TRIANGLE])
  {
    EXPECT_FALSE(facesOfKept.count(f)) << "a triangle of a kept tetrahedron is not output";
    used.insert(f.begin(), f.end());
  }
  for (const Cell& v : cells[VTK_VERTEX])
    used.insert(v.begin(), v.end());
  EXPECT_EQ(used.size(), p.size() / 3);
}

// The points a locator of tolerance `tolerance` merges, as vtkPointLocator does: in input order,
// each point within the tolerance of one kept before it.
std::vector<bool> MergedWithin(const fd3test::Points& p, double tolerance)
{
  std::vector<bool> merged(p.size() / 3, false);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < merged.size(); ++i)
  {
    for (const std::size_t k : kept)
    {
      double d2 = 0;
      for (int a = 0; a < 3; ++a)
        d2 += (p[3 * i + a] - p[3 * k + a]) * (p[3 * i + a] - p[3 * k + a]);
      merged[i] = merged[i] || d2 <= tolerance * tolerance;
    }
    if (!merged[i])
      kept.push_back(i);
  }
  return merged;
}

// A Locator merges as vtkDelaunay3D's: a point within its tolerance (a distance) of an earlier
// one is left out and counted with the skipped points; the rest are exactly tetrahedralized; the
// locator's changes re-execute the filter, and its use in a run does not.
TEST(Parity, LocatorMergesWithinItsTolerance)
{
  fd3test::Points p = fd3test::uniformCube(1000, 28);
  p.insert(p.end(), {p[0] + 4e-4, p[1], p[2], p[3] + 2e-3, p[4], p[5]});
  auto cloud = toPolyData(p);
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  ours->ComputeDensityOn();
  ours->Update();
  EXPECT_EQ(ours->GetNumberOfInsertedPoints(), 1002); // the kernel merges exact duplicates only
  ours->CreateDefaultLocator();                       // tolerance 0.001
  for (const double tolerance : {0.001, 0.005})
  {
    ours->GetLocator()->SetTolerance(tolerance);
    ours->Update();
    const std::vector<bool> merged = MergedWithin(p, tolerance);
    const auto count = static_cast<vtkIdType>(std::count(merged.begin(), merged.end(), true));
    ASSERT_GE(count, 1);
    EXPECT_EQ(ours->GetNumberOfSkippedPoints(), count) << tolerance;
    EXPECT_EQ(ours->GetNumberOfInsertedPoints(), 1002 - count) << tolerance;
    EXPECT_EQ(ours->GetNumberOfInvalidPoints(), 0);
    fd3test::Points kept = p; // the merged points are no vertices
    for (std::size_t i = 0; i < merged.size(); ++i)
      if (merged[i])
        kept[3 * i] = std::nan("");
    const auto report = fd3test::checkTriangulation(
      kept.data(), kept.size() / 3, fd3test::tetrahedra(ours->GetOutput()));
    EXPECT_TRUE(report.valid()) << report.summary();
  }
  vtkDataArray* density = ours->GetOutput()->GetPointData()->GetArray("Density");
  ASSERT_NE(density, nullptr);
  EXPECT_EQ(density->GetTuple1(1000), density->GetTuple1(0)); // the merged point's is its own's
  const vtkMTimeType ran = ours->GetOutput()->GetMTime();
  ours->Update();
  ours->Update();
  EXPECT_EQ(ours->GetOutput()->GetMTime(), ran) << "the locator's use re-executed the filter";
  ours->SetLocator(nullptr);
  ours->Update();
  EXPECT_EQ(ours->GetNumberOfSkippedPoints(), 0);
}

// The incremental API keeps the caller's mesh the exact Delaunay tetrahedralization of the
// octahedron and the points inserted: its cells, but the holes, are that tetrahedralization's
// after every point, the holes are the cells deleted and not given again, the links follow, and
// a repeat, a NaN point and a point far outside the octahedron are counted or inserted.
TEST(Parity, IncrementalInsertionKeepsTheExactMesh)
{
  const fd3test::Points p = fd3test::lattice(4); // ties everywhere
  const vtkIdType n = static_cast<vtkIdType>(p.size() / 3) + 3;
  vtkNew<vtkFastDelaunay3D> ours;
  double centre[3] = {1.5, 1.5, 1.5};
  vtkPoints* points = vtkPoints::New();
  points->SetDataType(VTK_DOUBLE);
  vtkUnstructuredGrid* mesh = ours->InitPointInsertion(centre, 20, n, points);
  fd3test::Points all; // the octahedron, then the points inserted: what the mesh must be of
  for (vtkIdType k = 0; k < 6; ++k)
  {
    double x[3];
    points->GetPoint(n + k, x);
    all.insert(all.end(), x, x + 3);
  }
  std::vector<vtkIdType> idOf = {n, n + 1, n + 2, n + 3, n + 4, n + 5};
  vtkNew<vtkIdList> holes;
  auto insert = [&](vtkIdType id, double x, double y, double z) {
    double xyz[3] = {x, y, z};
    ours->InsertPoint(mesh, points, id, xyz, holes);
  };
  // The exact tetrahedralization of the same points in the same frame, from scratch: where points
  // are cospherical, the frame's coordinates decide which tetrahedra break the ties.
  const double everything[6] = {-DBL_MAX, DBL_MAX, -DBL_MAX, DBL_MAX, -DBL_MAX, DBL_MAX};
  const fd3::Frame frame = fd3::identityFrame(fd3::Bounds::fromMinMax(everything));
  auto expectExact = [&](const std::string& when) {
    const fd3::Triangulation exact =
      fd3::IncrementalDelaunay(all.data(), all.size() / 3, fd3::Options(), frame).release();
    std::set<Cell> expected, live;
    for (std::size_t t = 0; t < exact.numberOfTetrahedra(); ++t)
    {
      Cell c;
      for (int k = 0; k < 4; ++k)
        c.push_back(idOf[exact.tetrahedra[4 * t + k]]);
      std::sort(c.begin(), c.end());
      expected.insert(c);
    }
    const std::set<vtkIdType> holeSet(holes->begin(), holes->end());
    vtkNew<vtkIdList> cellsOfPoint;
    for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
    {
      if (holeSet.count(c))
        continue;
      vtkIdType size;
      const vtkIdType* ids;
      mesh->GetCellPoints(c, size, ids);
      Cell cell(ids, ids + size);
      std::sort(cell.begin(), cell.end());
      live.insert(cell);
      mesh->GetPointCells(ids[0], cellsOfPoint);
      EXPECT_NE(cellsOfPoint->IsId(c), -1) << when << ": the links know cell " << c;
    }
    EXPECT_EQ(live, expected) << when;
  };
  for (vtkIdType i = 0; i + 3 < n; ++i)
  {
    insert(i, p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    all.insert(all.end(), &p[3 * i], &p[3 * i] + 3);
    idOf.push_back(i);
    if (i % 16 == 15)
      expectExact("after point " + std::to_string(i));
  }
  insert(n - 3, p[0], p[1], p[2]);   // a repeat
  insert(n - 2, std::nan(""), 0, 0); // not finite
  insert(n - 1, 100, 0, 0);          // beyond the octahedron
  all.insert(all.end(), {100, 0, 0});
  idOf.push_back(n - 1);
  expectExact("at the end");
  EXPECT_EQ(ours->GetNumberOfInsertedPoints(), n - 2);
  EXPECT_EQ(ours->GetNumberOfDuplicatePoints(), 1);
  EXPECT_EQ(ours->GetNumberOfInvalidPoints(), 1);
  ours->EndPointInsertion();
  mesh->Delete();
}

TEST(Parity, ProgressMovesDuringInsertion)
{
  auto cloud = toPolyData(fd3test::uniformCube(100000, 27));
  vtkNew<vtkFastDelaunay3D> ours;
  ours->SetInputData(cloud);
  std::vector<double> seen;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&seen);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(call));
  });
  ours->AddObserver(vtkCommand::ProgressEvent, onProgress);
  ours->Update();
  ASSERT_GE(seen.size(), 4u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GT(seen[seen.size() / 2], 0.0);
  EXPECT_LT(seen[seen.size() / 2], 1.0);
}

} // namespace
