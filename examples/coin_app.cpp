// A Coin3D (Open Inventor) application, the paper's own stack, as such programs are written: a scene
// graph of camera, light, material and an indexed face set, drawn by SoGLRenderAction into the
// application's own OpenGL 2.1 window (GLFW here; SoQt and Quarter do the same inside Qt).
// coin_app.cpp is the program as it was, coin_app_deformed.cpp the same with palpate's deformation as
// a shader node in the scene graph (README.md shows the diff).
// Usage: coin_app [--headless OUT.png] [--mesh FILE.ply]   (the mesh in millimetres)
#include <GLFW/glfw3.h>
#include <Inventor/SbViewportRegion.h>
#include <Inventor/SoDB.h>
#include <Inventor/actions/SoGLRenderAction.h>
#include <Inventor/elements/SoGLCacheContextElement.h>
#include <Inventor/nodes/SoCoordinate3.h>
#include <Inventor/nodes/SoDirectionalLight.h>
#include <Inventor/nodes/SoIndexedFaceSet.h>
#include <Inventor/nodes/SoMaterial.h>
#include <Inventor/nodes/SoNormal.h>
#include <Inventor/nodes/SoNormalBinding.h>
#include <Inventor/nodes/SoPerspectiveCamera.h>
#include <Inventor/nodes/SoRotationXYZ.h>
#include <Inventor/nodes/SoSeparator.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "palpate/core/load.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/png.hpp"

int main(int argc, char** argv) {
  const char* headless = nullptr;
  const char* mesh_file = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--headless") == 0) headless = argv[i + 1];
    if (std::strcmp(argv[i], "--mesh") == 0) mesh_file = argv[i + 1];
  }
  constexpr int width = 800, height = 800;
  if (!glfwInit()) return 1;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
  glfwWindowHint(GLFW_VISIBLE, headless ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, "coin app", nullptr, nullptr);
  if (!window) return 1;
  glfwMakeContextCurrent(window);
  SoDB::init();

  auto* root = new SoSeparator;
  root->ref();
  auto* camera = new SoPerspectiveCamera;
  camera->position.setValue(0, -170, 40);
  camera->pointAt(SbVec3f(0, 0, 0), SbVec3f(0, 0, 1));
  camera->heightAngle = float(40.0 * M_PI / 180.0);
  camera->nearDistance = 10;
  camera->farDistance = 500;
  root->addChild(camera);
  auto* light = new SoDirectionalLight;
  light->direction.setValue(0.6f, 0.5f, -0.6f);
  root->addChild(light);
  auto* material = new SoMaterial;
  material->diffuseColor.setValue(0.9f, 0.72f, 0.62f);
  root->addChild(material);
  auto* spin = new SoRotationXYZ;
  spin->axis = SoRotationXYZ::Z;
  root->addChild(spin);

  const palpate::Mesh mesh = mesh_file ? palpate::load_mesh(mesh_file) : palpate::make_sphere(50.0f, 40000);
  std::vector<SbVec3f> points, normals;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    points.emplace_back(mesh.positions_mm[v].x, mesh.positions_mm[v].y, mesh.positions_mm[v].z);
    normals.emplace_back(mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z);
  }
  std::vector<int32_t> faces;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    faces.insert(faces.end(), {int32_t(mesh.indices[t]), int32_t(mesh.indices[t + 1]),
                               int32_t(mesh.indices[t + 2]), SO_END_FACE_INDEX});
  }
  auto* coordinates = new SoCoordinate3;
  coordinates->point.setValues(0, int(points.size()), points.data());
  root->addChild(coordinates);
  auto* normal = new SoNormal;
  normal->vector.setValues(0, int(normals.size()), normals.data());
  root->addChild(normal);
  auto* binding = new SoNormalBinding;
  binding->value = SoNormalBinding::PER_VERTEX_INDEXED;
  root->addChild(binding);
  auto* face_set = new SoIndexedFaceSet;
  face_set->coordIndex.setValues(0, int(faces.size()), faces.data());
  root->addChild(face_set);

  const uint32_t cache_context = SoGLCacheContextElement::getUniqueCacheContext();
  const auto draw_frame = [&](int w, int h, double time_s) {
    spin->angle = float(0.3 * time_s);
    glViewport(0, 0, w, h);
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);  // a viewer's part, as SoRenderManager's
    SoGLRenderAction action{SbViewportRegion(short(w), short(h))};
    action.setCacheContext(cache_context);
    action.apply(root);
  };

  if (headless) {
    draw_frame(width, height, 0.0);
    std::vector<std::uint8_t> pixels(std::size_t(width) * height * 4);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    palpate::gl::save_png(headless, width, height, pixels);
    std::printf("wrote %s\n", headless);
  } else {
    for (double t = 0.0; !glfwWindowShouldClose(window); t += 1.0 / 60.0) {
      int w = 0, h = 0;
      glfwGetFramebufferSize(window, &w, &h);
      draw_frame(w, h, t);
      glfwSwapBuffers(window);
      glfwPollEvents();
    }
  }
  root->unref();
  glfwTerminate();
  return 0;
}
