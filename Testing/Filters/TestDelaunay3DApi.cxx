// Every public method of vtkDelaunay3D, called as a program written for vtkDelaunay3D calls them.
// The same source is built twice, for DELAUNAY_CLASS vtkDelaunay3D and vtkFastDelaunay3D (its
// header DELAUNAY_HEADER): only the class name changes between the two, and both must compile and
// pass. What it checks holds for both: property ranges and clamps, the locator and its modification
// time, the incremental API's mesh (positive tetrahedra on the inserted points once the holes and
// the octahedron's cells are skipped), and a pipeline run.
#include DELAUNAY_HEADER

#include "vtkCellArray.h"
#include "vtkIdList.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkPointLocator.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include <cstdlib>
#include <iostream>
#include <set>
#include <sstream>
#include <string>

namespace
{
int failures = 0;

void Expect(bool condition, const std::string& what)
{
  if (!condition)
  {
    std::cerr << "TestDelaunay3DApi: FAILED: " << what << "\n";
    ++failures;
  }
}

double SixVolume(vtkPoints* points, const vtkIdType* ids)
{
  double p[4][3];
  for (int k = 0; k < 4; ++k)
  {
    points->GetPoint(ids[k], p[k]);
  }
  double u[3], v[3], w[3];
  for (int a = 0; a < 3; ++a)
  {
    u[a] = p[1][a] - p[0][a];
    v[a] = p[2][a] - p[0][a];
    w[a] = p[3][a] - p[0][a];
  }
  return u[0] * (v[1] * w[2] - v[2] * w[1]) + u[1] * (v[2] * w[0] - v[0] * w[2]) +
    u[2] * (v[0] * w[1] - v[1] * w[0]);
}

void TypeAndPrint()
{
  vtkSmartPointer<DELAUNAY_CLASS> filter = vtkSmartPointer<DELAUNAY_CLASS>::New();
  Expect(DELAUNAY_CLASS::IsTypeOf("vtkUnstructuredGridAlgorithm"), "IsTypeOf");
  Expect(filter->IsA("vtkAlgorithm") != 0, "IsA");
  Expect(DELAUNAY_CLASS::SafeDownCast(filter) == filter, "SafeDownCast");
  vtkSmartPointer<DELAUNAY_CLASS> other = vtk::TakeSmartPointer(filter->NewInstance());
  Expect(other != nullptr && other != filter, "NewInstance");
  Expect(DELAUNAY_CLASS::GetNumberOfGenerationsFromBaseType("vtkAlgorithm") >= 1 &&
      filter->GetNumberOfGenerationsFromBase("vtkAlgorithm") >= 1,
    "GetNumberOfGenerationsFromBase(Type)");
  std::ostringstream printed;
  filter->Print(printed); // PrintSelf
  for (const char* field : {"Alpha:", "Tolerance:", "Offset:", "Bounding Triangulation:",
         "Locator:", "Output Points Precision:"})
  {
    Expect(printed.str().find(field) != std::string::npos, std::string("PrintSelf shows ") + field);
  }
}

void Properties()
{
  vtkNew<DELAUNAY_CLASS> filter;
  Expect(filter->GetAlpha() == 0.0 && filter->GetAlphaMinValue() == 0.0 &&
      filter->GetAlphaMaxValue() >= 1e299,
    "Alpha's default and range");
  filter->SetAlpha(-1);
  Expect(filter->GetAlpha() == 0.0, "Alpha clamped");
  filter->SetAlpha(0.25);
  Expect(filter->GetAlpha() == 0.25, "Alpha set");
  filter->SetAlphaTets(0);
  filter->AlphaTrisOff();
  filter->AlphaLinesOff();
  filter->AlphaVertsOff();
  Expect(!filter->GetAlphaTets() && !filter->GetAlphaTris() && !filter->GetAlphaLines() &&
      !filter->GetAlphaVerts(),
    "Alpha flags off");
  filter->AlphaTetsOn();
  filter->SetAlphaTris(1);
  filter->SetAlphaLines(1);
  filter->AlphaVertsOn();
  Expect(filter->GetAlphaTets() && filter->GetAlphaTris() && filter->GetAlphaLines() &&
      filter->GetAlphaVerts(),
    "Alpha flags on");
  Expect(filter->GetToleranceMinValue() == 0.0 && filter->GetToleranceMaxValue() == 1.0,
    "Tolerance's range");
  filter->SetTolerance(2);
  Expect(filter->GetTolerance() == 1.0, "Tolerance clamped");
  filter->SetTolerance(0.01);
  Expect(filter->GetTolerance() == 0.01, "Tolerance set");
  Expect(filter->GetOffset() == 2.5 && filter->GetOffsetMinValue() == 2.5 &&
      filter->GetOffsetMaxValue() >= 1e299,
    "Offset's default and range");
  filter->SetOffset(1);
  Expect(filter->GetOffset() == 2.5, "Offset clamped");
  filter->SetOffset(5);
  Expect(filter->GetOffset() == 5, "Offset set");
  Expect(!filter->GetBoundingTriangulation(), "BoundingTriangulation off by default");
  filter->BoundingTriangulationOn();
  Expect(filter->GetBoundingTriangulation() != 0, "BoundingTriangulationOn");
  filter->SetBoundingTriangulation(0);
  filter->BoundingTriangulationOff();
  Expect(filter->GetOutputPointsPrecision() == vtkAlgorithm::DEFAULT_PRECISION,
    "OutputPointsPrecision's default");
  filter->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  Expect(filter->GetOutputPointsPrecision() == vtkAlgorithm::DOUBLE_PRECISION,
    "OutputPointsPrecision set");
}

void Locator()
{
  vtkNew<DELAUNAY_CLASS> filter;
  Expect(filter->GetLocator() == nullptr, "no locator before one is set or made");
  filter->CreateDefaultLocator();
  Expect(vtkPointLocator::SafeDownCast(filter->GetLocator()) != nullptr,
    "CreateDefaultLocator makes a vtkPointLocator");
  vtkNew<vtkPointLocator> locator;
  filter->SetLocator(locator);
  Expect(filter->GetLocator() == locator.Get(), "SetLocator");
  const vtkMTimeType before = filter->GetMTime();
  locator->SetTolerance(0.5);
  Expect(filter->GetMTime() > before, "GetMTime counts the locator's");
  filter->SetLocator(nullptr);
  Expect(filter->GetLocator() == nullptr, "SetLocator(nullptr)");
}

void IncrementalInsertion()
{
  vtkNew<DELAUNAY_CLASS> filter;
  const vtkIdType n = 200;
  double center[3] = {0.5, 0.5, 0.5};
  vtkPoints* points = vtkPoints::New(); // the mesh takes this reference
  points->SetDataType(VTK_DOUBLE);
  points->Allocate(n + 6);
  vtkUnstructuredGrid* mesh = filter->InitPointInsertion(center, 10, n, points);
  Expect(mesh != nullptr && mesh->GetPoints() == points, "InitPointInsertion's mesh and points");
  Expect(mesh->GetNumberOfCells() > 0, "the octahedron's tetrahedra");
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(3);
  vtkNew<vtkIdList> holes;
  for (vtkIdType id = 0; id < n; ++id)
  {
    double x[3];
    for (double& c : x)
    {
      random->Next();
      c = random->GetValue();
    }
    filter->InsertPoint(mesh, points, id, x, holes);
  }
  filter->EndPointInsertion();
  const std::set<vtkIdType> holeSet(holes->begin(), holes->end());
  vtkIdType tetrahedra = 0, flat = 0;
  std::set<vtkIdType> used;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    vtkIdType size;
    const vtkIdType* ids;
    mesh->GetCellPoints(c, size, ids);
    bool onOctahedron = false;
    for (vtkIdType k = 0; k < size; ++k)
    {
      onOctahedron = onOctahedron || ids[k] >= n;
    }
    if (holeSet.count(c) || onOctahedron || size != 4)
    {
      continue;
    }
    ++tetrahedra;
    flat += SixVolume(points, ids) <= 0;
    used.insert(ids, ids + 4);
  }
  Expect(tetrahedra > n, "the incremental mesh holds the points' tetrahedra");
  Expect(flat == 0, "every tetrahedron of the incremental mesh is positive");
  Expect(used.size() > std::size_t(n) / 2, "the inserted points are the tetrahedra's");
  mesh->Delete();
}

void Pipeline()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(7);
  for (int i = 0; i < 300; ++i)
  {
    double x[3];
    for (double& c : x)
    {
      random->Next();
      c = random->GetValue();
    }
    points->InsertNextPoint(x);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  vtkNew<DELAUNAY_CLASS> filter;
  filter->SetInputData(cloud);
  filter->SetTolerance(0);
  filter->Update();
  vtkUnstructuredGrid* out = filter->GetOutput();
  Expect(out->GetNumberOfPoints() == 300 && out->GetNumberOfCells() > 1000, "a pipeline run");
  const vtkMTimeType run = filter->GetMTime();
  filter->Update();
  Expect(filter->GetMTime() == run, "Update leaves the modification time");
  vtkIdType flat = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    vtkIdType size;
    const vtkIdType* ids;
    out->GetCellPoints(c, size, ids);
    flat += size == 4 && SixVolume(out->GetPoints(), ids) <= 0;
  }
  Expect(flat == 0, "every output tetrahedron is positive");
}
} // namespace

int main()
{
  TypeAndPrint();
  Properties();
  Locator();
  IncrementalInsertion();
  Pipeline();
  if (failures == 0)
  {
    std::cout << "TestDelaunay3DApi: " << vtkNew<DELAUNAY_CLASS>()->GetClassName() << " OK\n";
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
