// vtkFastDelaunay3D through VTK: the output contract, checked with the exact validator.
#include "VtkTestUtilities.h"
#include "vtkFastDelaunay3D.h"

#include <gtest/gtest.h>

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStructuredGrid.h"
#include "vtkTestErrorObserver.h"
#include "vtkTetra.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace
{
using fd3test::checkOutput;
std::thread::id gCaller; // the thread that runs the filter, for progress observers
using fd3test::toPolyData;

TEST(Filter, KeepsPointsAndPointDataAndProducesExactTetrahedra)
{
  for (int type : {VTK_DOUBLE, VTK_FLOAT})
  {
    auto cloud = toPolyData(fd3test::uniformBall(3000, 4), type);
    vtkNew<vtkDoubleArray> index;
    index->SetName("Index");
    index->SetNumberOfValues(3000);
    for (vtkIdType i = 0; i < 3000; ++i)
      index->SetValue(i, static_cast<double>(i));
    cloud->GetPointData()->AddArray(index);
    vtkNew<vtkFastDelaunay3D> filter;
    filter->SetInputData(cloud);
    filter->Update();
    vtkUnstructuredGrid* out = filter->GetOutput();
    ASSERT_EQ(out->GetNumberOfPoints(), cloud->GetNumberOfPoints());
    EXPECT_EQ(out->GetPoints(), cloud->GetPoints()) << "input points are passed, not copied";
    ASSERT_NE(out->GetPointData()->GetArray("Index"), nullptr);
    EXPECT_EQ(out->GetPointData()->GetArray("Index")->GetNumberOfTuples(), 3000);
    EXPECT_EQ(out->GetNumberOfCells(), filter->GetNumberOfTetrahedra());
    for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
      ASSERT_EQ(out->GetCellType(c), VTK_TETRA);
    const auto report = checkOutput(out);
    EXPECT_TRUE(report.valid()) << report.summary();
  }
}

TEST(Filter, OutputCellsOutliveTheFilterAndGrow)
{
  // The tetrahedra are handed to the output's cell array without a copy: the cells must stay
  // valid after the filter and its kernel are gone and after the filter runs again, and the
  // array must grow like any other when cells are added. (On several threads the order of the
  // tetrahedra may differ from run to run: `first` is a copy of the first run's.)
  auto cloud = toPolyData(fd3test::uniformBall(2000, 7), VTK_DOUBLE);
  vtkNew<vtkUnstructuredGrid> kept, first;
  {
    vtkNew<vtkFastDelaunay3D> filter;
    filter->SetInputData(cloud);
    filter->Update();
    kept->ShallowCopy(filter->GetOutput());
    first->DeepCopy(filter->GetOutput());
    cloud->Modified();
    filter->Update(); // a new output array; kept holds the first one
    ASSERT_NE(filter->GetOutput()->GetCells(), kept->GetCells());
  }
  ASSERT_GT(kept->GetNumberOfCells(), 0);
  ASSERT_EQ(kept->GetNumberOfCells(), first->GetNumberOfCells());
  vtkNew<vtkIdList> a, b;
  for (vtkIdType c = 0; c < kept->GetNumberOfCells(); ++c)
  {
    kept->GetCellPoints(c, a);
    first->GetCellPoints(c, b);
    ASSERT_EQ(a->GetNumberOfIds(), 4);
    for (vtkIdType k = 0; k < 4; ++k)
      ASSERT_EQ(a->GetId(k), b->GetId(k)) << "cell " << c;
  }
  const auto report = checkOutput(kept);
  EXPECT_TRUE(report.valid()) << report.summary();

  const vtkIdType cells = kept->GetNumberOfCells();
  const vtkIdType extra[4] = {0, 1, 2, 3};
  for (int i = 0; i < 1000; ++i)
    kept->InsertNextCell(VTK_TETRA, 4, extra);
  ASSERT_EQ(kept->GetNumberOfCells(), cells + 1000);
  for (vtkIdType c = 0; c < cells; ++c)
  {
    kept->GetCellPoints(c, a);
    first->GetCellPoints(c, b);
    for (vtkIdType k = 0; k < 4; ++k)
      ASSERT_EQ(a->GetId(k), b->GetId(k)) << "cell " << c << " after growing";
  }
  kept->GetCellPoints(cells + 999, a);
  EXPECT_EQ(a->GetId(3), 3);
}

TEST(Filter, LatticeThroughStructuredGrid)
{
  const fd3test::Points p = fd3test::lattice(6);
  vtkNew<vtkPoints> points;
  for (std::size_t i = 0; i < p.size() / 3; ++i)
    points->InsertNextPoint(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
  vtkNew<vtkStructuredGrid> grid;
  grid->SetDimensions(6, 6, 6);
  grid->SetPoints(points);
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(grid);
  filter->Update();
  const auto report = checkOutput(filter->GetOutput());
  EXPECT_TRUE(report.valid()) << report.summary();
  EXPECT_EQ(report.usedVertices, 216u);
}

TEST(Filter, DuplicatesAreMergedAndReported)
{
  fd3test::Points p = fd3test::uniformCube(500, 3);
  p.insert(p.end(), p.begin(), p.begin() + 3 * 50);
  auto cloud = toPolyData(p);
  vtkNew<vtkFastDelaunay3D> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(cloud);
  filter->Update();
  EXPECT_EQ(filter->GetNumberOfDuplicatePoints(), 50);
  EXPECT_EQ(filter->GetNumberOfInsertedPoints(), 500);
  EXPECT_EQ(observer->CheckWarningMessage("50 of 550 points are not vertices of the "
                                          "tetrahedralization (they remain in the output, unused): "
                                          "50 exact duplicates (merged"),
    0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 550);
}

// Density: one value per output point; duplicates carry their vertex's; the linear field
// through the values integrates over the tetrahedra to the number of points; off by default.
TEST(Filter, DensityIntegratesToThePoints)
{
  fd3test::Points p = fd3test::uniformCube(2000, 5);
  p.insert(p.end(), p.begin(), p.begin() + 3 * 20);
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(toPolyData(p));
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetPointData()->GetArray("Density"), nullptr);
  filter->ComputeDensityOn();
  filter->SetAlpha(0.05); // the density is the whole tetrahedralization's
  filter->Update();
  vtkDataArray* density = filter->GetOutput()->GetPointData()->GetArray("Density");
  ASSERT_NE(density, nullptr);
  ASSERT_EQ(density->GetNumberOfTuples(), 2020);
  for (vtkIdType i = 0; i < 20; ++i)
    EXPECT_EQ(density->GetTuple1(2000 + i), density->GetTuple1(i));
  filter->SetAlpha(0);
  filter->Update();
  vtkUnstructuredGrid* out = filter->GetOutput();
  density = out->GetPointData()->GetArray("Density");
  const std::vector<std::uint32_t> tets = fd3test::tetrahedra(out);
  double integral = 0;
  for (std::size_t t = 0; t < tets.size(); t += 4)
  {
    double x[4][3];
    for (int k = 0; k < 4; ++k)
      out->GetPoint(tets[t + k], x[k]);
    const double volume = std::fabs(vtkTetra::ComputeVolume(x[0], x[1], x[2], x[3]));
    double mean = 0;
    for (int k = 0; k < 4; ++k)
      mean += density->GetTuple1(tets[t + k]) / 4;
    integral += volume * mean;
  }
  EXPECT_NEAR(integral, 2020, 1e-9 * 2020);
}

/// Input points used by at least one output cell.
std::size_t UsedPoints(vtkUnstructuredGrid* grid)
{
  const std::vector<std::uint32_t> ids = fd3test::tetrahedra(grid);
  std::vector<bool> used(static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (std::uint32_t id : ids)
    used[id] = true;
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
}

double FieldValue(vtkUnstructuredGrid* grid, const char* name)
{
  vtkDataArray* array = grid->GetFieldData()->GetArray(name);
  return array ? array->GetTuple1(0) : -1;
}

// A dense cloud (nearest neighbours 1e-4 apart, far below 0.001 of the diagonal, as in LiDAR
// tiles): the defaults keep every point. A Tolerance that skips points says how many in one
// warning, with every other cause of left-out points, and in the getters and the field data.
TEST(Filter, DefaultsKeepEveryPointAndToleranceReportsWhatItSkips)
{
  fd3test::Points p = fd3test::clusters(20000, 20, 1e-3, 7);
  vtkNew<vtkFastDelaunay3D> filter;
  int warnings = 0;
  vtkNew<vtkCallbackCommand> countWarnings;
  countWarnings->SetClientData(&warnings);
  countWarnings->SetCallback(
    [](vtkObject*, unsigned long, void* count, void*) { ++*static_cast<int*>(count); });
  filter->AddObserver(vtkCommand::WarningEvent, countWarnings);
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(toPolyData(p));
  filter->Update();
  EXPECT_EQ(warnings, 0);
  EXPECT_EQ(UsedPoints(filter->GetOutput()), 20000u);
  EXPECT_EQ(filter->GetNumberOfInsertedPoints(), 20000);
  EXPECT_EQ(filter->GetOutput()->GetFieldData()->GetNumberOfArrays(), 0);

  p.insert(p.end(), p.begin(), p.begin() + 3 * 30); // 30 exact duplicates
  p.insert(p.end(), {std::nan(""), 0.5, 0.5});
  filter->SetInputData(toPolyData(p));
  filter->SetTolerance(0.001);
  filter->Update();
  const std::size_t distinctFinite = 20000;
  const std::size_t used = UsedPoints(filter->GetOutput());
  const vtkIdType skipped = filter->GetNumberOfSkippedPoints();
  EXPECT_GT(skipped, 10000) << "most cluster points lie within 0.001 of the diagonal";
  EXPECT_EQ(static_cast<std::size_t>(skipped), distinctFinite - used);
  EXPECT_EQ(filter->GetNumberOfInsertedPoints(), static_cast<vtkIdType>(used));
  EXPECT_EQ(warnings, 1);
  EXPECT_EQ(
    observer->CheckWarningMessage(std::to_string(20031 - used) + " of 20031 points are not " +
      "vertices of the tetrahedralization (they remain in the output, unused): 30 exact " +
      "duplicates (merged: points at one position make one vertex); " + std::to_string(skipped) +
      " within Tolerance of an inserted point (Tolerance 0 " +
      "keeps them); 1 with NaN or infinite coordinates (no position to triangulate)"),
    0);
  EXPECT_EQ(FieldValue(filter->GetOutput(), "NumberOfSkippedPoints"), skipped);
  EXPECT_EQ(FieldValue(filter->GetOutput(), "NumberOfDuplicatePoints"), 30);
  EXPECT_EQ(FieldValue(filter->GetOutput(), "NumberOfInvalidPoints"), 1);
}

TEST(Filter, BadInputGetsAMessageAndAWellDefinedOutput)
{
  vtkNew<vtkFastDelaunay3D> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->AddObserver(vtkCommand::ErrorEvent, observer);

  // Empty input: warning, empty output.
  filter->SetInputData(toPolyData({}));
  filter->Update();
  EXPECT_EQ(observer->CheckWarningMessage("no input points"), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);

  // Coplanar points (fewer than 4 affinely independent): warning, the points and no cells.
  fd3test::Points flat = fd3test::uniformCube(100, 1);
  for (std::size_t i = 0; i < 100; ++i)
    flat[3 * i + 2] = 0.5;
  filter->SetInputData(toPolyData(flat));
  filter->Update();
  EXPECT_EQ(observer->CheckWarningMessage("collinear or coplanar"), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 100);
  ASSERT_NE(filter->GetOutput()->GetCells(), nullptr);

  // Three points: too few.
  filter->SetInputData(toPolyData(fd3test::uniformCube(3, 1)));
  filter->Update();
  EXPECT_EQ(observer->CheckWarningMessage("fewer than 4 distinct points"), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 3);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);

  // NaN and Inf: a warning that counts them; the rest is tetrahedralized.
  fd3test::Points bad = fd3test::uniformCube(200, 2);
  bad[0] = std::nan("");
  bad[31] = -INFINITY;
  filter->SetInputData(toPolyData(bad));
  filter->Update();
  EXPECT_EQ(observer->CheckWarningMessage("2 with NaN or infinite coordinates"), 0);
  EXPECT_EQ(filter->GetNumberOfInsertedPoints(), 198);
  EXPECT_GT(filter->GetOutput()->GetNumberOfCells(), 0);
}

TEST(Filter, EveryKindOfDatasetAndCellsWithoutPoints)
{
  // Image data: its implicit points are made explicit and tetrahedralized (a 5^3 lattice).
  vtkNew<vtkImageData> image;
  image->SetDimensions(5, 5, 5);
  image->SetSpacing(0.5, 0.25, 1.0);
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(image);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 125);
  const auto report = checkOutput(filter->GetOutput());
  EXPECT_TRUE(report.valid()) << report.summary();

  // An unstructured grid is a point set like any other.
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(toPolyData(fd3test::uniformCube(300, 5))->GetPoints());
  filter->SetInputData(grid);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 300);
  EXPECT_GT(filter->GetOutput()->GetNumberOfCells(), 300);

  // Cells but no points: a warning and an empty output, no crash.
  vtkNew<vtkPolyData> broken;
  vtkNew<vtkCellArray> verts;
  verts->InsertNextCell(1);
  verts->InsertCellPoint(0);
  broken->SetVerts(verts);
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);
  filter->SetInputData(broken);
  filter->Update();
  EXPECT_EQ(observer->CheckWarningMessage("no input points"), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);
}

// The same tetrahedra whatever the number of threads, with one explicitly or from VTK's SMP
// tools (0, ParaView's setting: the STDThread backend here); progress from the calling thread.
TEST(Filter, SameTetrahedraForAnyNumberOfThreads)
{
  auto cloud = toPolyData(fd3test::uniformBall(120000, 11));
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(cloud);
  EXPECT_EQ(filter->GetNumberOfThreads(), 0);
  filter->SetNumberOfThreads(1);
  filter->Update();
  const auto reference = fd3test::canonicalTetrahedra(fd3test::tetrahedra(filter->GetOutput()));
  const auto report = checkOutput(filter->GetOutput());
  EXPECT_TRUE(report.valid()) << report.summary();
  const std::string backend = vtkSMPTools::GetBackend();
  vtkSMPTools::SetBackend("STDThread");
  EXPECT_GE(vtkSMPTools::GetEstimatedNumberOfThreads(), 2);
  const std::thread::id caller = std::this_thread::get_id();
  for (int threads : {2, 3, 0})
  {
    bool foreign = false;
    vtkNew<vtkCallbackCommand> onProgress;
    onProgress->SetClientData(&foreign);
    onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void*) {
      *static_cast<bool*>(client) |= std::this_thread::get_id() != gCaller;
    });
    gCaller = caller;
    const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, onProgress);
    filter->SetNumberOfThreads(threads);
    filter->Update();
    filter->RemoveObserver(tag);
    EXPECT_FALSE(foreign) << threads << " threads";
    EXPECT_EQ(fd3test::canonicalTetrahedra(fd3test::tetrahedra(filter->GetOutput())), reference)
      << threads << " threads";
  }
  vtkSMPTools::SetBackend(backend.c_str());
}

// Abort from a progress observer (what ParaView's Abort button does): an empty output (VTK's
// executive empties an aborted algorithm's output), and the same filter then runs to a correct
// result; on one thread and on several.
class AbortWithThreads : public ::testing::TestWithParam<int>
{};

TEST_P(AbortWithThreads, LeavesAnEmptyOutputAndTheFilterRunsAgain)
{
  auto cloud = toPolyData(fd3test::uniformCube(60000, 6));
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(cloud);
  filter->SetNumberOfThreads(GetParam());
  vtkNew<vtkCallbackCommand> abortOnProgress;
  abortOnProgress->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, abortOnProgress);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);

  filter->RemoveObserver(tag);
  filter->SetAbortExecute(0);
  filter->Modified();
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 60000);
  const auto report = checkOutput(filter->GetOutput());
  EXPECT_TRUE(report.valid()) << report.summary();
}
INSTANTIATE_TEST_SUITE_P(Filter, AbortWithThreads, ::testing::Values(1, 2));

// An internal failure in the middle of a run (here an exception thrown by a progress observer,
// through the kernel): an error, the points and no cells, no leak (the sanitizer build checks), and
// the filter runs correctly afterwards.
TEST(Filter, InternalFailureKeepsThePointsWithoutCellsAndTheFilterRunsAgain)
{
  auto cloud = toPolyData(fd3test::uniformCube(60000, 8));
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(cloud);
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::ErrorEvent, observer);
  bool failed = false; // fail once, inside the kernel's run (not on the executive's final event)
  vtkNew<vtkCallbackCommand> failOnProgress;
  failOnProgress->SetClientData(&failed);
  failOnProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
    bool& failedAlready = *static_cast<bool*>(client);
    if (!failedAlready && *static_cast<double*>(call) > 0.2)
    {
      failedAlready = true;
      throw std::runtime_error("simulated failure");
    }
  });
  const unsigned long tag = filter->AddObserver(vtkCommand::ProgressEvent, failOnProgress);
  filter->Update();
  ASSERT_TRUE(failed);
  // VTK's event dispatch references a command while it executes and misses the release when the
  // command throws: give that reference back so that LeakSanitizer judges our code alone.
  failOnProgress->UnRegister(nullptr);
  EXPECT_EQ(observer->CheckErrorMessage("Triangulation failed: simulated failure"), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 60000);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);

  filter->RemoveObserver(tag);
  filter->Modified();
  filter->Update();
  const auto report = checkOutput(filter->GetOutput());
  EXPECT_TRUE(report.valid()) << report.summary();
  EXPECT_EQ(report.usedVertices, 60000u);
}

} // namespace
