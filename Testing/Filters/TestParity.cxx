// Drop-in parity with vtkDelaunay3D: same defaults, same tetrahedra and alpha shapes where both
// are well defined, and the extra properties' contracts.
#include "VtkTestUtilities.h"
#include "vtkFastDelaunay3D.h"

#include <gtest/gtest.h>

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDelaunay3D.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <array>
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
  // every point); applied, 0.001 would drop most of a dense cloud, so ours is 0 (keeps every point).
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
