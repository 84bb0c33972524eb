// vtkFastVoronoi3D through VTK: one polyhedron per distinct point, read back by VTK's own
// vtkPolyhedron (closed, its volume ours) and through the XML writer and reader; the cell arrays
// and the input's point data on the cells; the same cells for any thread count; bad input.
#include "VtkTestUtilities.h"
#include "vtkFastDelaunay3D.h"
#include "vtkFastVoronoi3D.h"

#include <gtest/gtest.h>

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyhedron.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLUnstructuredGridReader.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <cmath>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkUnstructuredGrid> Cells(vtkPolyData* points, int threads = 1)
{
  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(points);
  voronoi->SetNumberOfThreads(threads);
  voronoi->Update();
  vtkSmartPointer<vtkUnstructuredGrid> out = voronoi->GetOutput();
  return out;
}

/// The volume a face stream encloses (divergence theorem, faces fanned from their first point).
double StreamVolume(vtkUnstructuredGrid* grid, vtkIdType faces, const vtkIdType* stream)
{
  double volume = 0;
  for (vtkIdType f = 0; f < faces; ++f)
  {
    const vtkIdType size = *stream++;
    double a[3], b[3], c[3];
    grid->GetPoint(stream[0], a);
    for (vtkIdType k = 1; k + 1 < size; ++k)
    {
      grid->GetPoint(stream[k], b);
      grid->GetPoint(stream[k + 1], c);
      volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6;
    }
    stream += size;
  }
  return volume;
}

TEST(VoronoiFilter, OnePolyhedronPerPointThatVtkReadsBack)
{
  auto cloud = fd3test::toPolyData(fd3test::generate("clusters", 2000, 5));
  vtkNew<vtkDoubleArray> label;
  label->SetName("Label");
  label->SetNumberOfValues(2000);
  for (vtkIdType i = 0; i < 2000; ++i)
    label->SetValue(i, 0.5 * double(i));
  cloud->GetPointData()->AddArray(label);
  auto out = Cells(cloud);
  ASSERT_EQ(out->GetNumberOfCells(), 2000);
  vtkCellData* cd = out->GetCellData();
  auto* generator = vtkIdTypeArray::SafeDownCast(cd->GetArray("GeneratorId"));
  auto* volume = vtkDoubleArray::SafeDownCast(cd->GetArray("Volume"));
  ASSERT_NE(generator, nullptr);
  ASSERT_NE(volume, nullptr);
  ASSERT_NE(cd->GetArray("SurfaceArea"), nullptr);
  ASSERT_NE(cd->GetArray("NumberOfFaces"), nullptr);
  ASSERT_NE(cd->GetArray("NumberOfNeighbors"), nullptr);
  ASSERT_NE(cd->GetArray("Label"), nullptr) << "the input's point data goes to the cells";
  double bounds[6];
  cloud->GetBounds(bounds);
  const double box = (bounds[1] - bounds[0]) * (bounds[3] - bounds[2]) * (bounds[5] - bounds[4]);
  EXPECT_NEAR(fd3test::sum(volume), box, 1e-9 * box);
  std::vector<bool> seen(2000, false);
  vtkNew<vtkGenericCell> cell;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    ASSERT_EQ(out->GetCellType(c), VTK_POLYHEDRON);
    const vtkIdType id = generator->GetValue(c);
    ASSERT_FALSE(seen[id]);
    seen[id] = true;
    EXPECT_EQ(cd->GetArray("Label")->GetTuple1(c), 0.5 * double(id));
    // The face stream as VTK holds it encloses the cell's volume.
    vtkIdType faces;
    const vtkIdType* stream;
    out->GetFaceStream(c, faces, stream);
    EXPECT_EQ(cd->GetArray("NumberOfFaces")->GetTuple1(c), double(faces));
    EXPECT_NEAR(StreamVolume(out, faces, stream), volume->GetValue(c), 1e-9 * box) << "cell " << c;
    // VTK's own polyhedron finds the generator inside its cell.
    double x[3];
    cloud->GetPoint(id, x);
    bool onTheBox = false;
    for (int a = 0; a < 3; ++a)
      onTheBox = onTheBox || x[a] == bounds[2 * a] || x[a] == bounds[2 * a + 1];
    out->GetCell(c, cell);
    auto* polyhedron = vtkPolyhedron::SafeDownCast(cell->GetRepresentativeCell());
    ASSERT_NE(polyhedron, nullptr);
    if (!onTheBox)
      EXPECT_EQ(polyhedron->IsInside(x, 1e-12), 1) << "cell " << c;
  }
  // Through the XML writer and reader, the cells and their data are the same.
  const std::string file = std::string(FD3_TEST_OUTPUT_DIR) + "/voronoi.vtu";
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(out);
  writer->SetFileName(file.c_str());
  ASSERT_EQ(writer->Write(), 1);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkUnstructuredGrid* back = reader->GetOutput();
  ASSERT_EQ(back->GetNumberOfCells(), out->GetNumberOfCells());
  EXPECT_EQ(back->GetNumberOfPoints(), out->GetNumberOfPoints());
  EXPECT_NEAR(fd3test::sum(back->GetCellData()->GetArray("Volume")), box, 1e-9 * box);
}

// Density on the cells: Fast Delaunay 3D's on their generators; absent unless asked for.
TEST(VoronoiFilter, DensityIsFastDelaunay3Ds)
{
  const fd3test::Points p = fd3test::uniformCube(3000, 4);
  auto points = fd3test::toPolyData(p);
  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(points);
  voronoi->Update();
  EXPECT_EQ(voronoi->GetOutput()->GetCellData()->GetArray("Density"), nullptr);
  voronoi->ComputeDensityOn();
  voronoi->Update();
  vtkNew<vtkFastDelaunay3D> delaunay;
  delaunay->SetInputData(points);
  delaunay->ComputeDensityOn();
  delaunay->Update();
  vtkDataArray* cells = voronoi->GetOutput()->GetCellData()->GetArray("Density");
  vtkDataArray* ids = voronoi->GetOutput()->GetCellData()->GetArray("GeneratorId");
  vtkDataArray* expected = delaunay->GetOutput()->GetPointData()->GetArray("Density");
  ASSERT_NE(cells, nullptr);
  ASSERT_EQ(cells->GetNumberOfTuples(), 3000);
  for (vtkIdType c = 0; c < 3000; ++c)
  {
    const double e = expected->GetTuple1(static_cast<vtkIdType>(ids->GetTuple1(c)));
    EXPECT_NEAR(cells->GetTuple1(c), e, 1e-9 * e) << "cell " << c;
  }
}

// The faces output: each shared face once (from the lower generator id), each box face, on the
// cells' points; a cell's surface area is the sum of its faces' areas there.
TEST(VoronoiFilter, FacesOnceEachWithTheirGenerators)
{
  auto points = fd3test::toPolyData(fd3test::uniformCube(2000, 9));
  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(points);
  voronoi->Update();
  EXPECT_EQ(voronoi->GetFacesOutput()->GetNumberOfCells(), 0);
  voronoi->GenerateFacesOn();
  voronoi->Update();
  vtkUnstructuredGrid* cells = voronoi->GetOutput();
  vtkPolyData* faces = voronoi->GetFacesOutput();
  EXPECT_EQ(faces->GetPoints(), cells->GetPoints());
  vtkDataArray* ids = faces->GetCellData()->GetArray("GeneratorIds");
  vtkDataArray* area = faces->GetCellData()->GetArray("Area");
  ASSERT_NE(ids, nullptr);
  ASSERT_NE(area, nullptr);
  ASSERT_EQ(ids->GetNumberOfComponents(), 2);
  vtkDataArray* faceCounts = cells->GetCellData()->GetArray("NumberOfFaces");
  vtkDataArray* neighborCounts = cells->GetCellData()->GetArray("NumberOfNeighbors");
  vtkIdType shared = 0, box = 0;
  for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
  {
    shared += static_cast<vtkIdType>(neighborCounts->GetTuple1(c));
    box += static_cast<vtkIdType>(faceCounts->GetTuple1(c) - neighborCounts->GetTuple1(c));
  }
  EXPECT_EQ(faces->GetNumberOfCells(), shared / 2 + box);
  std::vector<double> surface(2000, 0);
  for (vtkIdType f = 0; f < faces->GetNumberOfCells(); ++f)
  {
    const auto a = static_cast<vtkIdType>(ids->GetComponent(f, 0));
    const auto b = static_cast<vtkIdType>(ids->GetComponent(f, 1));
    EXPECT_TRUE(b == -1 || a < b) << "face " << f;
    surface[a] += area->GetTuple1(f);
    if (b >= 0)
      surface[b] += area->GetTuple1(f);
  }
  vtkDataArray* generator = cells->GetCellData()->GetArray("GeneratorId");
  vtkDataArray* surfaceArea = cells->GetCellData()->GetArray("SurfaceArea");
  for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
  {
    const double expected = surfaceArea->GetTuple1(c);
    EXPECT_NEAR(
      surface[static_cast<std::size_t>(generator->GetTuple1(c))], expected, 1e-9 * expected)
      << "cell " << c;
  }
}

TEST(VoronoiFilter, WithoutPolyhedraEachCellIsItsGeneratorWithTheSameArrays)
{
  auto points = fd3test::toPolyData(fd3test::generate("clusters", 3000, 5));
  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(points);
  voronoi->GenerateFacesOn();
  voronoi->Update();
  vtkNew<vtkUnstructuredGrid> polyhedra;
  polyhedra->ShallowCopy(voronoi->GetOutput());
  const vtkIdType faceCount = voronoi->GetFacesOutput()->GetNumberOfCells();
  voronoi->GeneratePolyhedraOff();
  voronoi->Update();
  vtkUnstructuredGrid* vertices = voronoi->GetOutput();
  ASSERT_EQ(vertices->GetNumberOfCells(), polyhedra->GetNumberOfCells());
  EXPECT_EQ(vertices->GetNumberOfPoints(), vertices->GetNumberOfCells());
  EXPECT_EQ(voronoi->GetFacesOutput()->GetNumberOfCells(), faceCount);
  vtkDataArray* generator = vertices->GetCellData()->GetArray("GeneratorId");
  for (vtkIdType c = 0; c < vertices->GetNumberOfCells(); ++c)
  {
    ASSERT_EQ(vertices->GetCellType(c), VTK_VERTEX);
    vtkNew<vtkIdList> ids;
    vertices->GetCellPoints(c, ids);
    ASSERT_EQ(ids->GetNumberOfIds(), 1);
    const auto id = static_cast<vtkIdType>(generator->GetTuple1(c));
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(vertices->GetPoint(ids->GetId(0))[k], points->GetPoint(id)[k]) << "cell " << c;
  }
  for (const char* name :
    {"GeneratorId", "Volume", "SurfaceArea", "NumberOfFaces", "NumberOfNeighbors"})
  {
    vtkDataArray* a = vertices->GetCellData()->GetArray(name);
    vtkDataArray* b = polyhedra->GetCellData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    for (vtkIdType c = 0; c < vertices->GetNumberOfCells(); ++c)
      ASSERT_EQ(a->GetTuple1(c), b->GetTuple1(c)) << name << ", cell " << c;
  }
}

TEST(VoronoiFilter, SameCellsForAnyThreadCount)
{
  auto cloud = fd3test::toPolyData(fd3test::generate("cube", 20000, 2));
  auto one = Cells(cloud, 1);
  auto many = Cells(cloud, 7);
  ASSERT_EQ(one->GetNumberOfCells(), many->GetNumberOfCells());
  ASSERT_EQ(one->GetNumberOfPoints(), many->GetNumberOfPoints());
  for (vtkIdType c = 0; c < one->GetNumberOfCells(); c += 13)
  {
    vtkNew<vtkIdList> s1, s2;
    one->GetFaceStream(c, s1);
    many->GetFaceStream(c, s2);
    ASSERT_EQ(s1->GetNumberOfIds(), s2->GetNumberOfIds());
    for (vtkIdType k = 0; k < s1->GetNumberOfIds(); ++k)
      ASSERT_EQ(s1->GetId(k), s2->GetId(k));
    EXPECT_EQ(one->GetCellData()->GetArray("Volume")->GetTuple1(c),
      many->GetCellData()->GetArray("Volume")->GetTuple1(c));
  }
  for (vtkIdType p = 0; p < one->GetNumberOfPoints(); p += 17)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(one->GetPoint(p)[k], many->GetPoint(p)[k]);
}

TEST(VoronoiFilter, BoundsClipTheCells)
{
  auto cloud = fd3test::toPolyData(fd3test::generate("ball", 3000, 3));
  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(cloud);
  voronoi->SetBounds(-0.5, 0.5, -0.4, 0.6, -2, 2);
  voronoi->Update(); // UseInputBounds is on: Bounds is not used
  EXPECT_EQ(voronoi->GetOutput()->GetNumberOfCells(), 3000);
  double inputBounds[6];
  cloud->GetBounds(inputBounds);
  double box = 1;
  for (int a = 0; a < 3; ++a)
    box *= inputBounds[2 * a + 1] - inputBounds[2 * a];
  EXPECT_NEAR(
    fd3test::sum(voronoi->GetOutput()->GetCellData()->GetArray("Volume")), box, 1e-9 * box);
  voronoi->UseInputBoundsOff();
  voronoi->Update();
  vtkUnstructuredGrid* out = voronoi->GetOutput();
  EXPECT_EQ(out->GetNumberOfCells(), 3000) << "a cell for every point, empty where outside";
  EXPECT_NEAR(fd3test::sum(out->GetCellData()->GetArray("Volume")), 4.0, 1e-9 * 4.0);
  double bounds[6];
  out->GetPoints()->GetBounds(bounds);
  EXPECT_GE(bounds[0], -0.5);
  EXPECT_LE(bounds[1], 0.5);
  EXPECT_GE(bounds[2], -0.4);
  EXPECT_LE(bounds[3], 0.6);
  vtkIdType empty = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
    empty += out->GetCellType(c) == VTK_EMPTY_CELL;
  EXPECT_GT(empty, 0);
}

TEST(VoronoiFilter, DuplicatesAndNonFinitePointsAreCountedAndReported)
{
  fd3test::Points p = fd3test::generate("cube", 500, 8);
  p.insert(p.end(), {p[3], p[4], p[5], NAN, 0, 0});
  auto cloud = fd3test::toPolyData(p);
  vtkNew<vtkFastVoronoi3D> voronoi;
  vtkNew<vtkTest::ErrorObserver> observer;
  voronoi->AddObserver(vtkCommand::WarningEvent, observer);
  voronoi->SetInputData(cloud);
  voronoi->Update();
  EXPECT_EQ(voronoi->GetOutput()->GetNumberOfCells(), 500);
  EXPECT_EQ(voronoi->GetNumberOfGenerators(), 500);
  EXPECT_EQ(voronoi->GetNumberOfDuplicatePoints(), 1);
  EXPECT_EQ(voronoi->GetNumberOfInvalidPoints(), 1);
  ASSERT_TRUE(observer->GetWarning());
  EXPECT_NE(observer->GetWarningMessage().find("1 exact duplicates"), std::string::npos)
    << observer->GetWarningMessage();
  vtkFieldData* fields = voronoi->GetOutput()->GetFieldData();
  ASSERT_NE(fields->GetArray("NumberOfDuplicatePoints"), nullptr);
  EXPECT_EQ(fields->GetArray("NumberOfInvalidPoints")->GetTuple1(0), 1);
}

TEST(VoronoiFilter, EmptyAndFlatInputGiveAWarningAndNoCells)
{
  for (const fd3test::Points& p : {fd3test::Points{}, fd3test::Points{NAN, 1, 2},
         fd3test::Points{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}})
  {
    vtkNew<vtkFastVoronoi3D> voronoi;
    vtkNew<vtkTest::ErrorObserver> observer;
    voronoi->AddObserver(vtkCommand::WarningEvent, observer);
    voronoi->SetInputData(fd3test::toPolyData(p));
    voronoi->Update();
    EXPECT_TRUE(observer->GetWarning()) << p.size() / 3 << " points";
    vtkUnstructuredGrid* out = voronoi->GetOutput();
    double volume = 0;
    if (auto* array = out->GetCellData()->GetArray("Volume"))
      volume = fd3test::sum(array);
    EXPECT_EQ(volume, 0) << p.size() / 3 << " points";
  }
}
} // namespace
