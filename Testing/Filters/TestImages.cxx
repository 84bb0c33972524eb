// VTK regression images of vtkFastDelaunay3D, one scene per test:
//   TestImages <Scene> -D <Data> -V <baseline.png> -T <output dir>
// Circumradius: the bundled cloud, whole cells on one side of a plane, shrunk, coloured by the
//   cells' circumradius; AlphaShape: the alpha shape of points sampled on a torus;
//   MolecularSurface: the weighted alpha shape of a molecule's atoms, radii grown by a probe;
//   BoundingTriangulation: the tetrahedra of a small cloud with the bounding octahedron.
#include "VtkTestUtilities.h"
#include "vtkFastDelaunay3D.h"

#include "vtkActor.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkDataSetMapper.h"
#include "vtkExtractGeometry.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkShrinkFilter.h"
#include "vtkTestUtilities.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace
{
/// Float coordinates, as the baselines were made with.
vtkSmartPointer<vtkPolyData> Cloud(const fd3test::Points& p)
{
  return fd3test::toPolyData(p, VTK_FLOAT);
}

/// Shows `cells` shrunk by `factor`, coloured by their cell array `name` over [0, maxValue].
void ShowShrunkCells(vtkAlgorithmOutput* cells, double factor, const char* name, double maxValue,
  vtkDataSetMapper* mapper)
{
  vtkNew<vtkShrinkFilter> shrink;
  shrink->SetInputConnection(cells);
  shrink->SetShrinkFactor(factor);
  mapper->SetInputConnection(shrink->GetOutputPort());
  mapper->SetScalarModeToUseCellFieldData();
  mapper->SelectColorArray(name);
  mapper->SetScalarRange(0.0, maxValue);
}

/// Fills the renderer for the named scene; returns false for an unknown name.
bool BuildScene(const std::string& scene, int argc, char* argv[], vtkRenderer* renderer)
{
  vtkNew<vtkFastDelaunay3D> delaunay;
  vtkNew<vtkDataSetMapper> mapper;
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  if (scene == "Circumradius")
  {
    char* fileName = vtkTestUtilities::ExpandDataFileName(argc, argv, "points.vtp");
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(fileName);
    delete[] fileName;
    delaunay->SetInputConnection(reader->GetOutputPort());
    delaunay->ComputeCircumradiusOn();
    vtkNew<vtkPlane> plane;
    plane->SetNormal(0, -1, 0);
    vtkNew<vtkExtractGeometry> half; // whole cells only
    half->SetInputConnection(delaunay->GetOutputPort());
    half->SetImplicitFunction(plane);
    half->ExtractBoundaryCellsOn();
    ShowShrunkCells(half->GetOutputPort(), 0.7, "Circumradius", 0.6, mapper);
    camera->SetPosition(3, -12, 8);
  }
  else if (scene == "AlphaShape")
  {
    delaunay->SetInputData(Cloud(fd3test::torusSurface(4000, 7)));
    delaunay->SetAlpha(0.12);
    mapper->SetInputConnection(delaunay->GetOutputPort());
    mapper->ScalarVisibilityOff();
    actor->GetProperty()->SetColor(0.85, 0.65, 0.35);
    camera->SetPosition(1, -3, 3);
  }
  else if (scene == "MolecularSurface")
  {
    // The weighted alpha shape of a molecule's atoms with radii grown by a water probe's 1.4:
    // at a small Alpha, the solvent-accessible balls' union as cells.
    std::vector<double> radii;
    auto atoms = Cloud(fd3test::molecule(600, 3, radii));
    vtkNew<vtkFloatArray> probed;
    probed->SetName("ProbeRadius");
    for (const double r : radii)
      probed->InsertNextValue(static_cast<float>(r + 1.4));
    atoms->GetPointData()->AddArray(probed);
    delaunay->SetInputData(atoms);
    delaunay->SetInputArrayToProcess(
      0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "ProbeRadius");
    delaunay->SetAlpha(0.5);
    delaunay->AlphaLinesOff();
    delaunay->AlphaVertsOff();
    mapper->SetInputConnection(delaunay->GetOutputPort());
    mapper->ScalarVisibilityOff();
    actor->GetProperty()->SetColor(0.45, 0.7, 0.85);
    camera->SetPosition(0, -3, 1);
  }
  else if (scene == "BoundingTriangulation")
  {
    delaunay->SetInputData(Cloud(fd3test::uniformBall(60, 4)));
    delaunay->BoundingTriangulationOn();
    delaunay->ComputeVolumeOn();
    ShowShrunkCells(delaunay->GetOutputPort(), 0.8, "Volume", 20.0, mapper);
    actor->GetProperty()->SetOpacity(0.6);
    camera->SetPosition(10, -14, 9);
  }
  else
  {
    return false;
  }
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCamera();
  renderer->SetBackground(0.32, 0.34, 0.43);
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
  {
    return EXIT_FAILURE;
  }
  if (!std::getenv("DISPLAY"))
  {
    return 125; // rendering needs an X server: reported as skipped
  }
  const std::string scene = argv[1];
  --argc; // the regression tester reads -D/-V/-T from the remaining arguments
  ++argv;
  vtkNew<vtkRenderer> renderer;
  if (!BuildScene(scene, argc, argv, renderer))
  {
    return EXIT_FAILURE;
  }
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  window->Render();
  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
