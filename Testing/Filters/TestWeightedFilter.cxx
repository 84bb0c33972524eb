// vtkFastDelaunay3D on weighted points: the regular tetrahedralization of a radii array, checked
// with the exact validator, hidden points kept and counted, the weighted alpha shape.
#include "VtkTestUtilities.h"
#include "vtkFastDelaunay3D.h"
#include "vtkFastVoronoi3D.h"

#include <gtest/gtest.h>

#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnstructuredGrid.h"

#include "fd3/Delaunay.h"
#include "fd3/Voronoi.h"

#include <cmath>
#include <random>
#include <vector>

namespace
{
/// uniformCube(n) with a "Radius" point array: radii in [0.002, 0.06], and one point in ten a
/// small ball inside a larger one, which hides it.
vtkSmartPointer<vtkPolyData> weightedCloud(std::size_t n, std::vector<double>& weights)
{
  fd3test::Points p = fd3test::uniformCube(n, 81);
  std::mt19937_64 random(82);
  std::uniform_real_distribution<double> radius(0.002, 0.06);
  std::vector<double> radii(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    radii[i] = radius(random);
    if (i % 10 == 9) // beside the point before it, a tenth of its radius
    {
      for (int k = 0; k < 3; ++k)
        p[3 * i + k] = p[3 * (i - 1) + k] + 0.001 * (k + 1);
      radii[i] = radii[i - 1] / 10;
    }
  }
  auto cloud = fd3test::toPolyData(p);
  vtkNew<vtkFloatArray> array; // any type of array
  array->SetName("Radius");
  array->SetNumberOfValues(static_cast<vtkIdType>(n));
  weights.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), static_cast<float>(radii[i]));
    const double r = static_cast<float>(radii[i]);
    weights[i] = r * r;
  }
  cloud->GetPointData()->AddArray(array);
  return cloud;
}

TEST(WeightedFilter, RadiiGiveTheRegularTetrahedralization)
{
  std::vector<double> weights;
  auto cloud = weightedCloud(4000, weights);
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(cloud);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
  vtkNew<vtkTest::ErrorObserver> warnings;
  filter->AddObserver(vtkCommand::WarningEvent, warnings);
  filter->Update();
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  vtkUnstructuredGrid* out = filter->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 4000);
  ASSERT_NE(out->GetPointData()->GetArray("Radius"), nullptr);
  EXPECT_GE(filter->GetNumberOfHiddenPoints(), 300);
  EXPECT_EQ(filter->GetNumberOfInsertedPoints() + filter->GetNumberOfHiddenPoints(), 4000);
  vtkDataArray* hidden = out->GetFieldData()->GetArray("NumberOfHiddenPoints");
  ASSERT_NE(hidden, nullptr);
  EXPECT_EQ(hidden->GetComponent(0, 0), filter->GetNumberOfHiddenPoints());

  // The same as Core's, which the validator checks with the hidden points it lists.
  const fd3test::Points p = fd3test::coordinates(out);
  const fd3::Triangulation core = fd3::triangulate(p.data(), weights.data(), 4000);
  fd3test::ValidityOptions check;
  check.weights = weights.data();
  check.hidden = core.hidden;
  const auto report = fd3test::checkOutput(out, check);
  EXPECT_TRUE(report.valid()) << report.summary();
  EXPECT_EQ(fd3test::canonicalTetrahedra(fd3test::tetrahedra(out)),
    fd3test::canonicalTetrahedra(core.tetrahedra));

  // Weights themselves: the same squares.
  vtkNew<vtkDoubleArray> weightArray;
  weightArray->SetName("Weight");
  for (const double w : weights)
    weightArray->InsertNextValue(w);
  cloud->GetPointData()->AddArray(weightArray);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Weight");
  filter->WeightsAreRadiiOff();
  filter->Update();
  EXPECT_EQ(fd3test::canonicalTetrahedra(fd3test::tetrahedra(filter->GetOutput())),
    fd3test::canonicalTetrahedra(core.tetrahedra));
}

TEST(WeightedFilter, WeightedAlphaShapeIsCoresAndLeavesHiddenPointsOut)
{
  std::vector<double> weights;
  auto cloud = weightedCloud(3000, weights);
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(cloud);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
  filter->SetAlpha(0.04);
  filter->Update();
  vtkUnstructuredGrid* out = filter->GetOutput();
  const fd3test::Points p = fd3test::coordinates(out);
  fd3::Options options;
  options.computeNeighbors = true;
  const fd3::Triangulation core = fd3::triangulate(p.data(), weights.data(), 3000, options);
  const fd3::AlphaComplex shape = fd3::alphaComplex(p.data(), weights.data(), 3000, core, 0.04);
  const std::size_t cells = shape.tetrahedra.size() + shape.triangles.size() / 3 +
    shape.lines.size() / 2 + shape.vertices.size();
  EXPECT_EQ(out->GetNumberOfCells(), static_cast<vtkIdType>(cells));
  EXPECT_GT(shape.tetrahedra.size(), 0u);
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    vtkIdType size;
    const vtkIdType* ids;
    out->GetCellPoints(c, size, ids);
    for (vtkIdType k = 0; k < size; ++k)
      ASSERT_FALSE(std::binary_search(
        core.hidden.begin(), core.hidden.end(), static_cast<std::uint32_t>(ids[k])));
  }
}

TEST(WeightedFilter, BadWeightsGetAMessageAndWellFormedOutput)
{
  std::vector<double> weights;
  auto cloud = weightedCloud(500, weights);
  vtkNew<vtkDoubleArray> pairs; // two components: not weights
  pairs->SetName("Pairs");
  pairs->SetNumberOfComponents(2);
  pairs->SetNumberOfTuples(500);
  pairs->Fill(1.0);
  cloud->GetPointData()->AddArray(pairs);
  vtkNew<vtkFastDelaunay3D> filter;
  filter->SetInputData(cloud);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Pairs");
  vtkNew<vtkTest::ErrorObserver> errors;
  filter->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  filter->Update();
  EXPECT_TRUE(errors->GetError());
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 500);
  EXPECT_EQ(filter->GetOutput()->GetNumberOfCells(), 0);

  // NaN and infinite radii: those points are left out as invalid, with a warning.
  vtkDataArray* radius = cloud->GetPointData()->GetArray("Radius");
  radius->SetComponent(3, 0, std::nan(""));
  radius->SetComponent(4, 0, INFINITY);
  radius->Modified();
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
  vtkNew<vtkTest::ErrorObserver> warnings;
  filter->AddObserver(vtkCommand::WarningEvent, warnings);
  filter->Update();
  EXPECT_TRUE(warnings->GetWarning());
  EXPECT_EQ(filter->GetNumberOfInvalidPoints(), 2);
  EXPECT_GT(filter->GetOutput()->GetNumberOfCells(), 0);
}
// Power cells: one per distinct point, a hidden point's empty, the volumes Core's, filling the box.
TEST(WeightedFilter, VoronoiGivesPowerCells)
{
  std::vector<double> weights;
  auto cloud = weightedCloud(3000, weights);
  vtkNew<vtkFastVoronoi3D> voronoi;
  voronoi->SetInputData(cloud);
  voronoi->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Radius");
  vtkNew<vtkTest::ErrorObserver> warnings;
  voronoi->AddObserver(vtkCommand::WarningEvent, warnings);
  voronoi->Update();
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  vtkUnstructuredGrid* out = voronoi->GetOutput();
  ASSERT_EQ(out->GetNumberOfCells(), 3000);
  const fd3test::Points p = fd3test::coordinates(vtkPointSet::SafeDownCast(cloud));
  const fd3::VoronoiCells core = fd3::voronoiCells(p.data(), weights.data(), 3000);
  EXPECT_EQ(voronoi->GetNumberOfHiddenPoints(), static_cast<vtkIdType>(core.stats.hiddenPoints));
  EXPECT_GE(voronoi->GetNumberOfHiddenPoints(), 250);
  vtkDataArray* hidden = out->GetFieldData()->GetArray("NumberOfHiddenPoints");
  ASSERT_NE(hidden, nullptr);
  EXPECT_EQ(hidden->GetComponent(0, 0), voronoi->GetNumberOfHiddenPoints());
  vtkDataArray* volume = out->GetCellData()->GetArray("Volume");
  vtkDataArray* generator = out->GetCellData()->GetArray("GeneratorId");
  ASSERT_NE(volume, nullptr);
  ASSERT_NE(generator, nullptr);
  std::vector<double> byPoint(3000, -1);
  for (std::size_t c = 0; c < core.numberOfCells(); ++c)
    byPoint[core.generators[c]] = core.volumes[c];
  double sum = 0;
  vtkIdType empty = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    const double v = volume->GetComponent(c, 0);
    EXPECT_EQ(v, byPoint[static_cast<std::size_t>(generator->GetComponent(c, 0))]);
    sum += v;
    empty += v == 0;
  }
  EXPECT_GE(empty, voronoi->GetNumberOfHiddenPoints());
  const fd3::Bounds box = fd3::finiteBounds(p.data(), 3000);
  const double boxVolume = box.extent(0) * box.extent(1) * box.extent(2);
  EXPECT_NEAR(sum, boxVolume, 1e-12 * boxVolume);
}
} // namespace
