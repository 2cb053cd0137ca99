// A VTK application as such programs are written (3D Slicer's and iMSTK's toolkit): a reader, point
// normals, a mapper, an actor with its material, a renderer and a window with an interactor.
// vtk_app.cpp is the program as it was, vtk_app_deformed.cpp the same with palpate's deformation in
// the actor's own shaders (README.md shows the diff).
// Usage: vtk_app [--headless OUT.png] [--mesh FILE.ply]   (the mesh in millimetres)
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkPLYReader.h>
#include <vtkPNGWriter.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkWindowToImageFilter.h>

#include <cstring>

int main(int argc, char** argv) {
  const char* headless = nullptr;
  const char* mesh_file = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--headless") == 0) headless = argv[i + 1];
    if (std::strcmp(argv[i], "--mesh") == 0) mesh_file = argv[i + 1];
  }
  vtkNew<vtkPLYReader> reader;
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(50.0);
  sphere->SetThetaResolution(200);
  sphere->SetPhiResolution(200);
  if (mesh_file) reader->SetFileName(mesh_file);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(mesh_file ? reader->GetOutputPort() : sphere->GetOutputPort());
  normals->SplittingOff();

  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.72, 0.62);
  actor->GetProperty()->SetSpecular(0.2);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.1, 0.12);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, -170, 40);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkRenderWindow> window;
  window->SetSize(800, 800);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);

  if (headless) {
    window->SetOffScreenRendering(1);
    window->Render();
    vtkNew<vtkWindowToImageFilter> capture;
    capture->SetInput(window);
    vtkNew<vtkPNGWriter> png;
    png->SetFileName(headless);
    png->SetInputConnection(capture->GetOutputPort());
    png->Write();
    return 0;
  }
  vtkNew<vtkRenderWindowInteractor> interactor;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  interactor->SetRenderWindow(window);
  window->Render();
  interactor->Start();
  return 0;
}
