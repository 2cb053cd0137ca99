// palpate's deformation as a Coin3D shader node, rendered by Coin itself (SoGLRenderAction into a
// framebuffer of palpate's headless compatibility context): against the same scene drawn by Coin's
// fixed function undeformed, and against Coin drawing palpate's CPU reference of the dented mesh. With a
// transform above the shapes, with several lights and per-vertex colours.
#include "palpate/coin/deform_shader.hpp"

#include <Inventor/SbViewportRegion.h>
#include <Inventor/SoDB.h>
#include <Inventor/actions/SoGLRenderAction.h>
#include <Inventor/elements/SoGLCacheContextElement.h>
#include <Inventor/nodes/SoCoordinate3.h>
#include <Inventor/nodes/SoDirectionalLight.h>
#include <Inventor/nodes/SoIndexedFaceSet.h>
#include <Inventor/nodes/SoMaterial.h>
#include <Inventor/nodes/SoMaterialBinding.h>
#include <Inventor/nodes/SoMatrixTransform.h>
#include <Inventor/nodes/SoNormal.h>
#include <Inventor/nodes/SoNormalBinding.h>
#include <Inventor/nodes/SoPerspectiveCamera.h>
#include <Inventor/nodes/SoPointLight.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShaderProgram.h>
#include <Inventor/nodes/SoSpotLight.h>
#include <epoxy/gl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "palpate/core/deform.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/png.hpp"
#include "picture_comparison.hpp"

namespace palpate::coin {
namespace {

constexpr int size = 400;
const glm::vec3 eye(0, -170, 40);

struct Lighting {
  bool several = false;  // a point light, a spot light, specular material, colours per vertex
};

// The scene a Coin application has: camera, lights, material, then the shape (under a transform).
SoSeparator* scene(const Mesh& mesh, const glm::mat4& model, Lighting lighting, SoShaderProgram* shader) {
  auto* root = new SoSeparator;
  root->ref();
  auto* camera = new SoPerspectiveCamera;
  camera->position.setValue(eye.x, eye.y, eye.z);
  camera->pointAt(SbVec3f(0, 0, 0), SbVec3f(0, 0, 1));
  camera->heightAngle = glm::radians(40.0f);
  camera->nearDistance = 10.0f;
  camera->farDistance = 500.0f;
  root->addChild(camera);
  auto* sun = new SoDirectionalLight;
  sun->direction.setValue(0.0f, 1.0f, 0.0f);
  root->addChild(sun);
  auto* material = new SoMaterial;
  material->diffuseColor.setValue(0.9f, 0.72f, 0.62f);
  if (lighting.several) {
    auto* bulb = new SoPointLight;
    bulb->location.setValue(-80, -120, 60);
    bulb->color.setValue(0.4f, 0.5f, 1.0f);
    root->addChild(bulb);
    auto* spot = new SoSpotLight;
    spot->location.setValue(60, -150, -20);
    spot->direction.setValue(-0.3f, 1.0f, 0.1f);
    spot->cutOffAngle = 0.35f;
    spot->dropOffRate = 0.3f;
    spot->intensity = 0.6f;
    root->addChild(spot);
    material->specularColor.setValue(0.5f, 0.5f, 0.5f);
    material->shininess = 0.3f;
    material->ambientColor.setValue(0.1f, 0.05f, 0.05f);
  }
  root->addChild(material);
  auto* transform = new SoMatrixTransform;
  SbMatrix matrix;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) matrix[c][r] = model[c][r];  // Coin's matrices act on row vectors
  transform->matrix = matrix;
  root->addChild(transform);
  if (shader) root->addChild(shader);

  std::vector<SbVec3f> points, normals;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    points.emplace_back(mesh.positions_mm[v].x, mesh.positions_mm[v].y, mesh.positions_mm[v].z);
    normals.emplace_back(mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z);
  }
  auto* coordinates = new SoCoordinate3;
  coordinates->point.setValues(0, int(points.size()), points.data());
  root->addChild(coordinates);
  auto* normal = new SoNormal;
  normal->vector.setValues(0, int(normals.size()), normals.data());
  root->addChild(normal);
  auto* normal_binding = new SoNormalBinding;
  normal_binding->value = SoNormalBinding::PER_VERTEX_INDEXED;
  root->addChild(normal_binding);
  if (lighting.several) {  // colours by height: v is the vertex's ring (both meshes index alike)
    auto* colours = new SoMaterial;
    std::vector<SbColor> diffuse;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const float z = 0.5f + 0.5f * std::cos(float(v) * 6.0f / float(mesh.vertex_count()));
      diffuse.emplace_back(0.5f + 0.4f * z, 0.8f - 0.3f * z, 0.6f);
    }
    colours->diffuseColor.setValues(0, int(diffuse.size()), diffuse.data());
    root->addChild(colours);
    auto* binding = new SoMaterialBinding;
    binding->value = SoMaterialBinding::PER_VERTEX_INDEXED;
    root->addChild(binding);
  }
  std::vector<int32_t> indices;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    indices.insert(indices.end(), {int32_t(mesh.indices[t]), int32_t(mesh.indices[t + 1]),
                                   int32_t(mesh.indices[t + 2]), SO_END_FACE_INDEX});
  }
  auto* faces = new SoIndexedFaceSet;
  faces->coordIndex.setValues(0, int(indices.size()), indices.data());
  root->addChild(faces);
  return root;
}

struct Picture {
  std::vector<std::uint8_t> rgba;
  int at(int x, int y, int c) const { return rgba[4 * std::size_t(y * size + x) + std::size_t(c)]; }
};

// Coin draws into palpate's framebuffer on a compatibility context, as an application's own window.
class CoinDeformShader : public testing::Test {
 protected:
  static void SetUpTestSuite() { SoDB::init(); }
  Picture render(SoSeparator* root) {
    framebuffer_.bind();
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);  // the viewer's part (SoRenderManager's), not the render action's
    SoGLRenderAction action(SbViewportRegion(size, size));
    action.setCacheContext(cache_context_);
    action.apply(root);
    glFinish();
    root->unref();
    return {framebuffer_.read_rgba8()};
  }

  gl::HeadlessContext context_{{.major_version = 2, .minor_version = 1, .compatibility = true}};
  gl::Framebuffer framebuffer_{{.width = size, .height = size}};
  uint32_t cache_context_ = SoGLCacheContextElement::getUniqueCacheContext();
};

test::PictureComparison compare(const Picture& a, const Picture& b, glm::vec2 centre_px, float reach_px) {
  return test::compare_pictures(a.rgba, b.rgba, size, size, 4, centre_px, reach_px);
}

glm::vec2 pixel_of(glm::vec3 world) {  // rows from the bottom, as glReadPixels gives them
  const glm::vec4 clip = glm::perspective(glm::radians(40.0f), 1.0f, 10.0f, 500.0f) *
                         glm::lookAt(eye, glm::vec3(0), glm::vec3(0, 0, 1)) * glm::vec4(world, 1.0f);
  return {(clip.x / clip.w * 0.5f + 0.5f) * size, (clip.y / clip.w * 0.5f + 0.5f) * size};
}

TEST_F(CoinDeformShader, DentsLikeTheCpuReferenceAndNowhereElse) {
  struct Case {
    const char* name;
    glm::mat4 model;
    Lighting lighting;
    bool per_fragment;
  };
  const glm::mat4 turned =
      glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(8, 5, -4)), 0.7f, glm::vec3(1, 1, 0.3f));
  for (const Case& c :
       {Case{"one light", glm::mat4(1.0f), {}, false}, Case{"under a transform", turned, {}, false},
        Case{"several lights, colours per vertex", glm::mat4(1.0f), {.several = true}, false},
        Case{"one light, per fragment", glm::mat4(1.0f), {}, true},
        Case{"under a transform, per fragment", turned, {}, true}}) {
    SCOPED_TRACE(c.name);
    const Mesh sphere = make_sphere(50.0f, 40000);
    // The contact on the side facing the camera, in world coordinates, and in the shape's own.
    const glm::vec3 contact = glm::normalize(glm::vec3(0.3f, -1.0f, 0.3f)) * 50.0f +
                              glm::vec3(c.model[3]);  // the sphere's centre is moved by the model matrix
    const Dent world_dent{contact, 6.0f, 8.0f};
    DeformShader shader({.lights = c.lighting.several ? 3 : 1, .per_fragment = c.per_fragment});
    const Dent object_dent = dent_in_space(world_dent, glm::inverse(c.model));
    EXPECT_EQ(shader.set({&object_dent, 1}), 0);

    // The references: Coin's fixed function drawing the sphere, and palpate's CPU reference of the
    // dented sphere (true normals at the vertices).
    const Picture undeformed = render(scene(sphere, c.model, c.lighting, nullptr));
    const Picture deformed = render(scene(sphere, c.model, c.lighting, shader.node()));
    Mesh reference;  // world coordinates: drawn with an identity transform
    deform_mesh(sphere, c.model, {&world_dent, 1}, reference);
    const Picture expected = render(scene(reference, glm::mat4(1.0f), c.lighting, nullptr));
    if (const char* folder = std::getenv("PALPATE_TEST_PICTURES"))  // to look at them
      gl::save_png(std::string(folder) + "/coin " + c.name + ".png", size, size, deformed.rgba);

    const glm::vec2 centre_px = pixel_of(contact);
    float reach_px = 0.0f;
    for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
      reach_px =
          std::max(reach_px, glm::distance(pixel_of(contact + axis * 4.0f * world_dent.sigma_mm), centre_px));
    const test::PictureComparison against_plain =
        compare(undeformed, deformed, centre_px, reach_px * 1.1f + 3.0f);
    const test::PictureComparison against_cpu =
        compare(expected, deformed, centre_px, reach_px * 1.1f + 3.0f);
    std::printf(
        "%s: dent %d px (%d beyond its reach); against the CPU reference: mean %.3f, worst %d (of 765)\n",
        c.name, against_plain.changed_near, against_plain.changed_far, against_cpu.mean, against_cpu.worst);
    EXPECT_GT(against_plain.changed_near, 1000) << "no dent";
    EXPECT_EQ(against_plain.changed_far, 0) << "changed beyond the dent's reach";
    EXPECT_LT(against_cpu.mean, 0.6) << "unlike the CPU reference";
    EXPECT_LE(against_cpu.worst, 36) << "unlike the CPU reference";
  }
}

TEST_F(CoinDeformShader, WithoutDentsItDrawsAsCoinsFixedFunction) {
  const Mesh sphere = make_sphere(50.0f, 40000);
  DeformShader shader({.dent_slots = 2, .lights = 3, .per_fragment = true});
  const Picture fixed = render(scene(sphere, glm::mat4(1.0f), {.several = true}, nullptr));
  const Picture shaded = render(scene(sphere, glm::mat4(1.0f), {.several = true}, shader.node()));
  const test::PictureComparison comparison = compare(fixed, shaded, glm::vec2(0), 0.0f);
  std::printf("without dents, against Coin's fixed function: mean %.3f, worst %d\n", comparison.mean,
              comparison.worst);
  // Measured: mean 0.006, worst 2 (rounding: the same equation per vertex, in GLSL).
  EXPECT_LT(comparison.mean, 0.02);
  EXPECT_LE(comparison.worst, 6);
}

TEST_F(CoinDeformShader, DentsBeyondItsSlotsAreCountedAndBadParametersAreErrors) {
  DeformShader shader({.dent_slots = 2});
  const Dent dents[3] = {{{0, -50, 0}, 3, 8}, {{10, -48, 0}, 3, 8}, {{-10, -48, 0}, 3, 8}};
  EXPECT_EQ(shader.set(dents), 1);
  EXPECT_EQ(shader.set({dents, 2}), 0);
  EXPECT_THAT([] { DeformShader bad({.dent_slots = 0}); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("dent_slots must be 1..")));
  EXPECT_THAT([] { DeformShader bad({.lights = 9}); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("lights must be 1..8")));
}

}  // namespace
}  // namespace palpate::coin
