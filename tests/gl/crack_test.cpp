// No cracks: a mesh whose vertices are split (flat shading, creases, parts that touch) stays closed
// under a dent, because every vertex at one position moves along one shared direction
// (Mesh::directions). Checked on the GPU (transform feedback of palpate_displace: corners that coincide
// at rest coincide dented) and in the picture (no background shows inside the undeformed silhouette);
// each check also runs with every corner moving along its own normal, to show that it would catch a
// crack.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <tuple>
#include <vector>

#include "gl_test_context.hpp"
#include "palpate/core/displacement.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/deform_uniforms.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/renderer.hpp"
#include "palpate/gl/shader_program.hpp"
#include "palpate/testing/test_shapes.hpp"
#include "test_paths.hpp"

namespace palpate::gl {
namespace {

// Every vertex through palpate_displace(position, direction) with `dents`, read back by transform
// feedback.
std::vector<glm::vec3> displaced_on_gpu(const Mesh& mesh, const std::vector<glm::vec3>& directions,
                                        std::span<const Dent> dents) {
  const std::string vertex = insert_deform_glsl(R"glsl(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 direction;
out vec3 displaced;
void main() { displaced = palpate_displace(position, direction); gl_Position = vec4(0.0); }
)glsl");
  const std::string fragment = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
  const GLuint program = glCreateProgram();
  for (const auto& [stage, text] :
       {std::pair{GLenum(GL_VERTEX_SHADER), vertex}, std::pair{GLenum(GL_FRAGMENT_SHADER), fragment}}) {
    const GLuint shader = glCreateShader(stage);
    const char* source = text.c_str();
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    glAttachShader(program, shader);
    glDeleteShader(shader);
  }
  const char* varying = "displaced";
  glTransformFeedbackVaryings(program, 1, &varying, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(program);
  DeformUniforms uniforms(program);
  uniforms.set(dents);

  const std::size_t n = mesh.vertex_count();
  GLuint vao = 0, buffers[3] = {};
  glCreateVertexArrays(1, &vao);
  glCreateBuffers(3, buffers);
  glNamedBufferStorage(buffers[0], GLsizeiptr(n * sizeof(glm::vec3)), mesh.positions_mm.data(), 0);
  glNamedBufferStorage(buffers[1], GLsizeiptr(n * sizeof(glm::vec3)), directions.data(), 0);
  glNamedBufferStorage(buffers[2], GLsizeiptr(n * sizeof(glm::vec3)), nullptr, 0);
  for (GLuint i = 0; i < 2; ++i) {
    glVertexArrayVertexBuffer(vao, i, buffers[i], 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(vao, i);
    glVertexArrayAttribFormat(vao, i, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, i, i);
  }
  const Framebuffer target({1, 1});
  target.bind();
  glUseProgram(program);
  uniforms.apply();
  glBindVertexArray(vao);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffers[2]);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, GLsizei(n));
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  std::vector<glm::vec3> out(n);
  glGetNamedBufferSubData(buffers[2], 0, GLsizeiptr(n * sizeof(glm::vec3)), out.data());
  glUseProgram(0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(3, buffers);
  glDeleteProgram(program);
  return out;
}

// The largest distance, after the dents, between vertices that share a position at rest.
float widest_crack(const Mesh& mesh, const std::vector<glm::vec3>& displaced) {
  const PositionGroups groups = group_positions(mesh, default_weld_tolerance_mm(mesh));
  std::vector<glm::vec3> first(groups.count);
  std::vector<bool> seen(groups.count, false);
  float widest = 0.0f;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const std::uint32_t g = groups.group[v];
    if (!seen[g]) {
      seen[g] = true;
      first[g] = displaced[v];
    }
    widest = std::max(widest, glm::distance(first[g], displaced[v]));
  }
  return widest;
}

// Dents of 3 and 5 mm at vertices of the mesh (sigma 4 and 8 mm): where split corners meet.
std::vector<Dent> dents_on(const Mesh& mesh) {
  return {{mesh.positions_mm[mesh.vertex_count() / 3], 3.0f, 4.0f},
          {mesh.positions_mm[2 * mesh.vertex_count() / 3], 5.0f, 8.0f}};
}

void expect_no_crack(Mesh mesh, const std::string& what) {
  test::gl_context();
  compute_displacement_directions(mesh);
  ASSERT_EQ(mesh.directions.size(), mesh.vertex_count()) << what << ": its vertices are split";
  const std::vector<Dent> dents = dents_on(mesh);
  const float shared = widest_crack(mesh, displaced_on_gpu(mesh, mesh.directions, dents));
  const float own = widest_crack(mesh, displaced_on_gpu(mesh, mesh.normals, dents));
  EXPECT_LE(shared, 1e-5f) << what;
  EXPECT_GT(own, 0.1f) << what << ": moved along their own normals, the corners should have parted";
  std::printf(
      "%s: widest gap between corners that coincide at rest: %.2g mm along shared directions, "
      "%.2f mm along their own normals\n",
      what.c_str(), shared, own);
}

TEST(NoCracks, FlatShadedTorus) {
  expect_no_crack(testing::split_flat(testing::make_torus(30.0f, 12.0f, 48, 24)), "flat torus");
}

TEST(NoCracks, FlatShadedSteppedBlock) {
  expect_no_crack(testing::split_flat(testing::make_comb(5, 8.0f, 6.0f, 10.0f, 8.0f, 40.0f)),
                  "flat stepped block");
}

TEST(NoCracks, CreasedAndFlatVrmlFiles) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  for (const char* file : {"vrml/castle_cubes_mesh_def_use.wrl", "vrml/castle_vrml1_shape_hints.wrl",
                           "vrml/castle_smoothing_independent_of_faces_order.wrl"}) {
    Mesh mesh = load_mesh(data / file);
    expect_no_crack(std::move(mesh), file);
  }
}

// The picture: the flat torus seen from above, dented 4 mm on top of its tube with a reach (4 sigma,
// 10 mm) that stays inside the silhouette (the tube's edges are 12 mm away): background pixels inside
// the undeformed silhouette are cracks.
int crack_pixels(const Mesh& mesh) {
  test::gl_context();
  Scene scene;
  SceneObject torus;
  torus.name = "torus";
  torus.mesh = mesh;
  torus.material.sigma_mm = 2.5f;
  scene.objects.push_back(torus);
  const glm::mat4 view = glm::lookAt(glm::vec3(0, -30, 60), glm::vec3(0, -30, 12), glm::vec3(0, 1, 0));
  const glm::mat4 projection = glm::perspective(glm::radians(40.0f), 1.0f, 10.0f, 400.0f);
  const ObjectDent dent{0, Dent{{0.0f, -30.0f, 12.0f}, 4.0f, 2.5f}};  // the top of the tube
  const auto draw = [&](Deformation deformation) {
    const Framebuffer target({400, 400});
    target.bind();
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    Renderer renderer;
    renderer.upload(scene);
    DrawParams params;
    params.deformation = deformation;
    renderer.draw(view, projection, std::span<const ObjectDent>(&dent, 1), params);
    return target.read_rgba8();
  };
  const auto rest = draw(Deformation::none), dented = draw(Deformation::gpu);
  int cracks = 0;
  for (std::size_t i = 3; i < rest.size(); i += 4) cracks += rest[i] == 255 && dented[i] == 0;
  return cracks;
}

TEST(NoCracks, NoBackgroundShowsThroughTheDentOfAFlatShadedTorus) {
  Mesh torus = testing::split_flat(testing::make_torus(30.0f, 12.0f, 32, 16));
  compute_displacement_directions(torus);
  const int shared = crack_pixels(torus);
  torus.directions.clear();  // every corner along its own normal
  const int own = crack_pixels(torus);
  EXPECT_EQ(shared, 0);
  EXPECT_GT(own, 10) << "the test cannot see cracks";
  std::printf("background pixels inside the silhouette: %d along shared directions, %d along own normals\n",
              shared, own);
}

}  // namespace
}  // namespace palpate::gl
