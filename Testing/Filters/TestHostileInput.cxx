// vtkFastDelaunay3D on what a careless or hostile user may bring: any finite magnitude, every
// property at the limits of its range, and inputs with no tetrahedron. Each run must end (ctest's
// timeout bounds it), give an exactly valid output with every distinct finite point a vertex, or
// the points and no cells with a message, and never crash.
#include "VtkTestUtilities.h"
#include "vtkFastDelaunay3D.h"

#include <gtest/gtest.h>

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <cfloat>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace
{
using fd3test::joined;
using fd3test::Points;
using fd3test::scaled;

/// The hostile sets of the issue that asked for them, by name.
std::vector<std::pair<std::string, Points>> hostileSets()
{
  std::vector<std::pair<std::string, Points>> sets;
  Points corners;
  for (int k = 0; k < 8; ++k)
    corners.insert(corners.end(),
      {k & 1 ? DBL_MAX : -DBL_MAX, k & 2 ? DBL_MAX : -DBL_MAX, k & 4 ? DBL_MAX : -DBL_MAX});
  sets.emplace_back(
    "corners at +-DBL_MAX beside unit data", joined(corners, fd3test::uniformCube(200, 1)));
  sets.emplace_back(
    "span above DBL_MAX", scaled(fd3test::uniformCube(2000, 2), 1.78e308, -8.9e307));
  sets.emplace_back("within 1e300", scaled(fd3test::uniformCube(1000, 3), 1e300));
  sets.emplace_back("within 1e-300", scaled(fd3test::uniformCube(1000, 4), 1e-300));
  sets.emplace_back("subnormal", scaled(fd3test::uniformCube(500, 5), 1e-310));
  for (double far : {1e100, 1e200, DBL_MAX})
    sets.emplace_back(
      "outlier at " + std::to_string(far), joined(fd3test::uniformCube(1000, 6), {far, 0, 0}));
  sets.emplace_back(
    "100 points and an outlier", joined(fd3test::uniformCube(100, 6), {1e100, 0, 0}));
  for (double spread : {1e-70, 1e-150, 1e-250}) // at 0, in the middle of unit data
    sets.emplace_back("cluster of spread " + std::to_string(spread),
      joined(scaled(fd3test::uniformCube(300, 7), 1, -0.5),
        scaled(fd3test::uniformCube(300, 8), spread)));
  return sets;
}

TEST(HostileInput, AnyFiniteMagnitudeOnOneAndTwoThreads)
{
  for (const auto& [name, points] : hostileSets())
    for (int threads : {1, 2})
    {
      vtkNew<vtkFastDelaunay3D> filter;
      filter->SetInputData(fd3test::toPolyData(points));
      filter->SetNumberOfThreads(threads);
      filter->Update();
      vtkUnstructuredGrid* out = filter->GetOutput();
      const std::string what = name + ", " + std::to_string(threads) + " threads";
      ASSERT_EQ(out->GetNumberOfPoints(), static_cast<vtkIdType>(points.size() / 3)) << what;
      const auto report = fd3test::checkOutput(out);
      EXPECT_TRUE(report.valid()) << what << ": " << report.summary();
      EXPECT_EQ(report.usedVertices, report.distinctPoints) << what;
      EXPECT_EQ(filter->GetNumberOfInsertedPoints(), static_cast<vtkIdType>(report.distinctPoints))
        << what;
    }
}

/// Runs the filter on a small cloud with one property set by `set`; the output must be a valid
/// tetrahedralization of every point (or, with an alpha, a set of cells over the input points).
void expectWellFormed(const std::string& what, const std::function<void(vtkFastDelaunay3D*)>& set,
  bool wholeTetrahedralization = true)
{
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(fd3test::toPolyData(fd3test::uniformCube(2000, 9)));
  set(filter);
  filter->Update();
  vtkUnstructuredGrid* out = filter->GetOutput();
  ASSERT_GE(out->GetNumberOfPoints(), 2000) << what;
  ASSERT_NE(out->GetCells(), nullptr) << what;
  if (!wholeTetrahedralization)
    return;
  const auto report = fd3test::checkOutput(out);
  EXPECT_TRUE(report.valid()) << what << ": " << report.summary();
  EXPECT_EQ(report.usedVertices, out->GetNumberOfPoints()) << what;
}

TEST(HostileInput, EveryNumericPropertyAtTheLimitsOfItsRange)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = HUGE_VAL;
  for (double v : {-inf, -1.0, 0.0, 1e-9, 1000.0, 1e9, 1e70, inf, nan})
  {
    const std::string value = std::to_string(v);
    expectWellFormed(
      "GridResolution " + value, [v](vtkFastDelaunay3D* f) { f->SetGridResolution(v); });
    expectWellFormed(
      "Tolerance " + value, [v](vtkFastDelaunay3D* f) { f->SetTolerance(v); },
      v <= 0 || std::isnan(v));
    expectWellFormed(
      "VolumeThreshold " + value, [v](vtkFastDelaunay3D* f) { f->SetVolumeThreshold(v); }, false);
    expectWellFormed(
      "Alpha " + value, [v](vtkFastDelaunay3D* f) { f->SetAlpha(v); }, !(v > 0));
    expectWellFormed("Offset " + value, [v](vtkFastDelaunay3D* f) {
      f->SetOffset(v);
      f->BoundingTriangulationOn();
    });
  }
  for (int threads : {-1, 0, 1, 64, 100000, std::numeric_limits<int>::max()})
    expectWellFormed("NumberOfThreads " + std::to_string(threads),
      [threads](vtkFastDelaunay3D* f) { f->SetNumberOfThreads(threads); });
  for (int seed : {std::numeric_limits<int>::min(), -1, 0, std::numeric_limits<int>::max()})
    expectWellFormed("RandomSeed " + std::to_string(seed),
      [seed](vtkFastDelaunay3D* f) { f->SetRandomSeed(seed); });

  // A NaN sets the documented default; values beyond the range are clamped to it.
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetOffset(nan);
  EXPECT_EQ(filter->GetOffset(), 2.5);
  filter->SetOffset(inf);
  EXPECT_EQ(filter->GetOffset(), VTK_DOUBLE_MAX);
  filter->SetGridResolution(nan);
  EXPECT_EQ(filter->GetGridResolution(), 4.0);
  filter->SetTolerance(-inf);
  EXPECT_EQ(filter->GetTolerance(), 0.0);
  filter->SetAlpha(nan);
  EXPECT_EQ(filter->GetAlpha(), 0.0);
}

TEST(HostileInput, WarningsCountInEveryMode)
{
  vtkNew<vtkFastDelaunay3D> filter;
  vtkNew<vtkTest::ErrorObserver> observer;
  filter->AddObserver(vtkCommand::WarningEvent, observer);

  // With the bounding octahedron's 6 points added: one duplicate of 1001 input points.
  Points p = fd3test::uniformCube(1000, 10);
  p.insert(p.end(), p.begin(), p.begin() + 3);
  filter->SetInputData(fd3test::toPolyData(p));
  filter->BoundingTriangulationOn();
  filter->Update();
  EXPECT_EQ(observer->CheckWarningMessage("1 of 1001 points are not vertices"), 0);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 1007);

  // An Offset of NaN is the default: nothing left out, no warning.
  filter->SetOffset(std::nan(""));
  filter->SetInputData(fd3test::toPolyData(fd3test::uniformCube(1000, 10)));
  filter->Update();
  EXPECT_FALSE(observer->GetWarning());
  EXPECT_EQ(filter->GetNumberOfInsertedPoints(), 1006);
  EXPECT_TRUE(fd3test::checkOutput(filter->GetOutput()).valid());

  // All NaN: every point counted once, as not finite.
  filter->BoundingTriangulationOff();
  filter->SetInputData(fd3test::toPolyData(Points(300, std::nan(""))));
  filter->Update();
  EXPECT_EQ(observer->CheckWarningMessage("no finite input point"), 0);
  EXPECT_EQ(filter->GetNumberOfInvalidPoints(), 100);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 100);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);
}

/// Writes `grid` in `mode` and reads it back.
vtkSmartPointer<vtkUnstructuredGrid> roundTrip(
  vtkUnstructuredGrid* grid, int mode, const std::string& file)
{
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName(file.c_str());
  writer->SetDataMode(mode);
  EXPECT_EQ(writer->Write(), 1) << file;
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutput();
}

TEST(HostileInput, OutputsWithoutTetrahedraWriteAndReadBackInEveryMode)
{
  Points coplanar = fd3test::uniformCube(50, 11);
  for (std::size_t i = 2; i < coplanar.size(); i += 3)
    coplanar[i] = 0.25;
  const std::vector<std::pair<std::string, Points>> inputs = {{"coplanar", coplanar},
    {"three points", fd3test::uniformCube(3, 12)}, {"all NaN", Points(30, std::nan(""))},
    {"empty", Points()}};
  for (const auto& [name, points] : inputs)
  {
    auto input = fd3test::toPolyData(points);
    vtkNew<vtkDoubleArray> values; // point data must come through too
    values->SetName("values");
    values->SetNumberOfValues(static_cast<vtkIdType>(points.size() / 3));
    for (vtkIdType i = 0; i < values->GetNumberOfValues(); ++i)
      values->SetValue(i, double(i));
    input->GetPointData()->AddArray(values);
    vtkNew<vtkFastDelaunay3D> filter;
    vtkNew<vtkTest::ErrorObserver> observer; // the warnings are expected here
    filter->AddObserver(vtkCommand::WarningEvent, observer);
    filter->SetInputData(input);
    filter->Update();
    vtkUnstructuredGrid* out = filter->GetOutput();
    ASSERT_EQ(out->GetNumberOfPoints(), static_cast<vtkIdType>(points.size() / 3)) << name;
    ASSERT_NE(out->GetCells(), nullptr) << name;
    EXPECT_EQ(out->GetNumberOfCells(), 0) << name;
    EXPECT_NE(out->GetPointData()->GetArray("values"), nullptr) << name;
    const int modes[] = {vtkXMLWriter::Ascii, vtkXMLWriter::Binary, vtkXMLWriter::Appended};
    for (int mode : modes)
    {
      const std::string file =
        std::string(FD3_TEST_OUTPUT_DIR) + "/hostile-" + std::to_string(mode) + ".vtu";
      vtkSmartPointer<vtkUnstructuredGrid> back = roundTrip(out, mode, file);
      EXPECT_EQ(back->GetNumberOfPoints(), out->GetNumberOfPoints()) << name << ", mode " << mode;
      EXPECT_EQ(back->GetNumberOfCells(), 0) << name << ", mode " << mode;
    }
  }
}

} // namespace
