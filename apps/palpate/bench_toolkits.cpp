#include "bench_toolkits.hpp"

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
#include <Inventor/nodes/SoSeparator.h>
#include <epoxy/gl.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <cstdio>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <memory>

#include "palpate/coin/deform_shader.hpp"
#include "palpate/core/deform.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/vtk/actor_deformation.hpp"

namespace palpate::cli {
namespace {

// Coin: camera, a light from the eye, then one separator per object {material, [palpate's node],
// geometry}; the plain root and the deformed ones (lit per vertex, lit per fragment) share the geometry.
class CoinScenes {
 public:
  CoinScenes(const Scene& scene, const ToolkitView& view, const Dent& world_dent, std::size_t touched)
      : target_({.width = view.width, .height = view.height}) {
    for (SoSeparator*& root : roots_) {
      root = new SoSeparator;
      root->ref();
    }
    auto* camera = new SoPerspectiveCamera;
    camera->position.setValue(view.eye.x, view.eye.y, view.eye.z);
    camera->pointAt(SbVec3f(view.center.x, view.center.y, view.center.z), SbVec3f(0, 0, 1));
    camera->heightAngle = view.fov_rad;
    camera->nearDistance = view.near_mm;
    camera->farDistance = view.far_mm;
    auto* light = new SoDirectionalLight;
    const glm::vec3 ahead = glm::normalize(view.center - view.eye);
    light->direction.setValue(ahead.x, ahead.y, ahead.z);
    for (SoSeparator* root : roots_) {
      root->addChild(camera);
      root->addChild(light);
    }
    const Dent object_dent = dent_in_space(world_dent, glm::inverse(scene.objects[touched].transform));
    per_vertex_.set({&object_dent, 1});
    per_fragment_.set({&object_dent, 1});
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      const SceneObject& object = scene.objects[o];
      auto* geometry = new SoSeparator;
      auto* material = new SoMaterial;
      material->diffuseColor.setValue(object.material.color.r, object.material.color.g,
                                      object.material.color.b);
      geometry->addChild(material);
      std::vector<SbVec3f> points, normals;  // world mm, as the renderer's rows draw them
      const glm::mat3 rotation(object.transform);
      for (std::size_t v = 0; v < object.mesh.vertex_count(); ++v) {
        const glm::vec3 p = glm::vec3(object.transform * glm::vec4(object.mesh.positions_mm[v], 1.0f));
        const glm::vec3 n = rotation * object.mesh.normals[v];
        points.emplace_back(p.x, p.y, p.z);
        normals.emplace_back(n.x, n.y, n.z);
      }
      auto* coordinates = new SoCoordinate3;
      coordinates->point.setValues(0, int(points.size()), points.data());
      auto* normal = new SoNormal;
      normal->vector.setValues(0, int(normals.size()), normals.data());
      auto* binding = new SoNormalBinding;
      binding->value = SoNormalBinding::PER_VERTEX_INDEXED;
      std::vector<int32_t> indices;
      for (std::size_t t = 0; t < object.mesh.indices.size(); t += 3) {
        indices.insert(indices.end(), {int32_t(object.mesh.indices[t]), int32_t(object.mesh.indices[t + 1]),
                                       int32_t(object.mesh.indices[t + 2]), SO_END_FACE_INDEX});
      }
      auto* faces = new SoIndexedFaceSet;
      faces->coordIndex.setValues(0, int(indices.size()), indices.data());
      for (SoNode* node : std::initializer_list<SoNode*>{coordinates, normal, binding, faces})
        geometry->addChild(node);
      roots_[0]->addChild(geometry);
      for (int lit = 1; lit <= 2; ++lit) {
        auto* deformed = new SoSeparator;
        if (o == touched) deformed->addChild((lit == 1 ? per_vertex_ : per_fragment_).node());
        deformed->addChild(geometry);
        roots_[lit]->addChild(deformed);
      }
    }
  }
  void release() const noexcept { context_.release(); }
  ~CoinScenes() {
    for (SoSeparator* root : roots_) root->unref();
  }
  CoinScenes(const CoinScenes&) = delete;
  CoinScenes& operator=(const CoinScenes&) = delete;

  // 0: plain, 1: deformed and lit per vertex, 2: per fragment.
  void draw(int root, const ToolkitView& view) {
    context_.make_current();
    target_.bind();
    glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    SoGLRenderAction action{SbViewportRegion(short(view.width), short(view.height))};
    action.setCacheContext(cache_context_);
    action.apply(roots_[root]);
    glFinish();
    context_.release();  // for VTK's GLX context
  }

 private:
  gl::HeadlessContext context_{{.major_version = 2, .minor_version = 1, .compatibility = true}};
  gl::Framebuffer target_;
  uint32_t cache_context_ = SoGLCacheContextElement::getUniqueCacheContext();
  coin::DeformShader per_vertex_, per_fragment_{{.per_fragment = true}};
  SoSeparator* roots_[3] = {};
};

// VTK: one offscreen window per variant, one actor per object on shared poly data; VTK's headlight.
class VtkWindow {
 public:
  VtkWindow(const std::vector<vtkSmartPointer<vtkPolyData>>& objects, const Scene& scene,
            const ToolkitView& view, const Dent* world_dent, std::size_t touched) {
    for (std::size_t o = 0; o < objects.size(); ++o) {
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(objects[o]);
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      const glm::vec3 colour = scene.objects[o].material.color;
      actor->GetProperty()->SetColor(colour.r, colour.g, colour.b);
      renderer_->AddActor(actor);
      if (world_dent && o == touched) {
        deformation_ = std::make_unique<vtk::ActorDeformation>(actor, renderer_);
        deformation_->set({world_dent, 1});
      }
    }
    renderer_->SetBackground(0.08, 0.08, 0.1);
    vtkCamera* camera = renderer_->GetActiveCamera();
    camera->SetPosition(view.eye.x, view.eye.y, view.eye.z);
    camera->SetFocalPoint(view.center.x, view.center.y, view.center.z);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(glm::degrees(view.fov_rad));
    camera->SetClippingRange(view.near_mm, view.far_mm);
    window_->SetOffScreenRendering(1);
    window_->SetMultiSamples(0);
    window_->SetSize(view.width, view.height);
    window_->AddRenderer(renderer_);
  }
  void draw() {
    window_->Render();
    window_->WaitForCompletion();
    window_->ReleaseCurrent();  // for Coin's EGL context
  }

 private:
  vtkNew<vtkRenderWindow> window_;
  vtkNew<vtkRenderer> renderer_;
  std::unique_ptr<vtk::ActorDeformation> deformation_;
};

std::vector<vtkSmartPointer<vtkPolyData>> vtk_objects(const Scene& scene) {
  std::vector<vtkSmartPointer<vtkPolyData>> objects;
  for (const SceneObject& object : scene.objects) {
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> normals;
    normals->SetNumberOfComponents(3);
    const glm::mat3 rotation(object.transform);
    for (std::size_t v = 0; v < object.mesh.vertex_count(); ++v) {
      const glm::vec3 p = glm::vec3(object.transform * glm::vec4(object.mesh.positions_mm[v], 1.0f));
      const glm::vec3 n = rotation * object.mesh.normals[v];
      points->InsertNextPoint(p.x, p.y, p.z);
      normals->InsertNextTuple3(n.x, n.y, n.z);
    }
    vtkNew<vtkCellArray> triangles;
    for (std::size_t t = 0; t < object.mesh.indices.size(); t += 3) {
      const vtkIdType ids[3] = {object.mesh.indices[t], object.mesh.indices[t + 1],
                                object.mesh.indices[t + 2]};
      triangles->InsertNextCell(3, ids);
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(points);
    poly->SetPolys(triangles);
    poly->GetPointData()->SetNormals(normals);
    objects.push_back(poly);
  }
  return objects;
}

}  // namespace

std::vector<ToolkitTally> bench_toolkits(const Scene& scene, const ToolkitView& view, const Contact& contact,
                                         double seconds, int rounds) {
  const std::size_t touched = contact.object;
  const Dent dent = dent_from_contact(contact, scene.objects[touched].material.sigma_mm);
  SoDB::init();  // once per process; later calls return at once
  CoinScenes coin(scene, view, dent, touched);
  coin.release();
  std::vector<std::pair<const char*, const char*>> names{
      {"coin", "plain"}, {"coin", "deform"}, {"coin", "deform-per-fragment"}};
  std::vector<std::function<void()>> frames{[&] { coin.draw(0, view); }, [&] { coin.draw(1, view); },
                                            [&] { coin.draw(2, view); }};

  std::unique_ptr<VtkWindow> vtk_plain, vtk_deformed;
  const char* display = std::getenv("DISPLAY");
  if (display && *display) {
    const auto objects = vtk_objects(scene);
    vtk_plain = std::make_unique<VtkWindow>(objects, scene, view, nullptr, touched);
    vtk_deformed = std::make_unique<VtkWindow>(objects, scene, view, &dent, touched);
    names.insert(names.end(), {{"vtk", "plain"}, {"vtk", "deform"}});
    frames.insert(frames.end(), {[&] { vtk_plain->draw(); }, [&] { vtk_deformed->draw(); }});
  } else {
    std::printf(
        "  (no VTK rows: Debian's VTK draws through X and there is no DISPLAY; run under xvfb-run -a)\n");
  }
  for (const auto& frame : frames) frame();  // warm-up: shader compilation
  const std::vector<Tally> tallies = measure_interleaved(frames, seconds, rounds);
  std::vector<ToolkitTally> rows;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    rows.push_back({names[i].first, names[i].second, tallies[i]});
  }
  return rows;
}

}  // namespace palpate::cli
