// Image regression: the bundled point cloud tetrahedralized, whole cells on one side of a plane
// shown shrunk and coloured by the points' scalar.
#include "vtkFastDelaunay3D.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataSetMapper.h"
#include "vtkExtractGeometry.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkShrinkFilter.h"
#include "vtkTestUtilities.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>

int main(int argc, char* argv[])
{
  if (!std::getenv("DISPLAY"))
  {
    return 125; // rendering needs an X server: reported as skipped
  }
  char* fileName = vtkTestUtilities::ExpandDataFileName(argc, argv, "points.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(fileName);
  delete[] fileName;

  vtkNew<vtkFastDelaunay3D> delaunay;
  delaunay->SetInputConnection(reader->GetOutputPort());
  vtkNew<vtkPlane> plane;
  plane->SetNormal(0, -1, 0);
  vtkNew<vtkExtractGeometry> half; // whole cells only
  half->SetInputConnection(delaunay->GetOutputPort());
  half->SetImplicitFunction(plane);
  half->ExtractBoundaryCellsOn();
  vtkNew<vtkShrinkFilter> shrink;
  shrink->SetInputConnection(half->GetOutputPort());
  shrink->SetShrinkFactor(0.7);
  vtkNew<vtkDataSetMapper> mapper;
  mapper->SetInputConnection(shrink->GetOutputPort());
  mapper->SetScalarRange(-1.5, 1.5);
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.32, 0.34, 0.43);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 300);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  renderer->GetActiveCamera()->SetPosition(3, -12, 8);
  renderer->GetActiveCamera()->SetViewUp(0, 0, 1);
  renderer->ResetCamera();
  window->Render();

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}
