// The GLSL deformation against its CPU twin (palpate/core/deform.hpp), read back by transform feedback,
// in every dialect (GLSL 1.10 and 1.20 on a compatibility context, 1.40 to 4.50 and ES 3.00 on a core
// one), fed by DeformUniforms; the std140 block against the layout the driver reports; the insertion
// after #version, #extension and #pragma lines.
#include "palpate/gl/deform_glsl.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <string>
#include <vector>

#include "gl_test_context.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/core/surface_patch.hpp"
#include "palpate/gl/deform_uniforms.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/shader_program.hpp"

namespace palpate::gl {
namespace {

// A vertex shader that feeds the snippet's functions with each vertex and captures their results, in
// the words of its GLSL version; `along_surface`: the overloads that take the surface sample.
std::string capture_vertex(const std::string& version, bool along_surface = false) {
  const bool old = version == "110" || version == "120";
  const std::string in = old ? "attribute" : "in", out = old ? "varying" : "out";
  const std::string surface = along_surface ? ", palpate_surface_varying(position, surface)" : "";
  return "#version " + version + "\n" + in + " vec3 position;\n" + in + " vec3 normal;\n" + in +
         " vec4 surface;\n" + out + " vec3 displaced;\n" + out + " vec3 perturbed;\n" + out +
         " vec3 fragment_displaced;\n" +
         "void main() {\n  displaced = palpate_displace(position, normalize(normal)" + surface +
         ");\n  perturbed = palpate_perturb_normal(normal, position" + surface + R"glsl();
  vec3 n = normalize(normal);
  fragment_displaced = position;
  palpate_deform_fragment(fragment_displaced, n)glsl" +
         surface + R"glsl();
  gl_Position = vec4(0.0);
}
)glsl";
}

std::string empty_fragment(const std::string& version) {
  if (version == "110" || version == "120")
    return "#version " + version + "\nvoid main() { gl_FragColor = vec4(1.0); }\n";
  const std::string precision = version.find("es") != std::string::npos ? "precision mediump float;\n" : "";
  return "#version " + version + "\n" + precision + "out vec4 c;\nvoid main() { c = vec4(1.0); }\n";
}

GLuint compile(GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[4096] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    ADD_FAILURE() << "does not compile: " << log << "\n" << source;
  }
  return shader;
}

// A compatibility-profile context, for GLSL 1.10 and 1.20 (a core profile starts at 1.40).
gl::HeadlessContext& compatibility_context() {
  static gl::HeadlessContext context({.major_version = 4, .minor_version = 5, .compatibility = true});
  context.make_current();
  return context;
}

struct Captured {
  std::vector<glm::vec3> displaced, perturbed, fragment_displaced;
};

// Runs `mesh`'s vertices (as points, rasterizer off) through the snippet in the GLSL `version`, with
// `dents` fed by DeformUniforms, on the current context; with `surface_samples` (one per vertex), through
// the functions that take them.
Captured capture(const Mesh& mesh, std::span<const Dent> dents, int dent_slots = max_dents,
                 const std::string& version = "450 core", std::span<const glm::vec4> surface_samples = {}) {
  const GLuint program = glCreateProgram();
  const GLuint vs = compile(
      GL_VERTEX_SHADER, insert_deform_glsl(capture_vertex(version, !surface_samples.empty()), dent_slots));
  const GLuint fs = compile(GL_FRAGMENT_SHADER, empty_fragment(version));
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glBindAttribLocation(program, 0, "position");
  glBindAttribLocation(program, 1, "normal");
  glBindAttribLocation(program, 2, "surface");
  const char* varyings[] = {"displaced", "perturbed", "fragment_displaced"};
  glTransformFeedbackVaryings(program, 3, varyings, GL_INTERLEAVED_ATTRIBS);
  glLinkProgram(program);
  GLint linked = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &linked);
  EXPECT_EQ(linked, GL_TRUE);

  DeformUniforms uniforms(program);
  uniforms.set(dents);

  const std::size_t n = mesh.vertex_count();
  GLuint vao = 0, buffers[4] = {};
  glCreateVertexArrays(1, &vao);
  glCreateBuffers(4, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(n * sizeof(glm::vec3)), mesh.positions_mm.data(),
                       0);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(n * sizeof(glm::vec3)), mesh.normals.data(), 0);
  glNamedBufferStorage(buffers[2], static_cast<GLsizeiptr>(3 * n * sizeof(glm::vec3)), nullptr, 0);
  for (GLuint i = 0; i < 2; ++i) {
    glVertexArrayVertexBuffer(vao, i, buffers[i], 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(vao, i);
    glVertexArrayAttribFormat(vao, i, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, i, i);
  }
  if (!surface_samples.empty()) {
    glNamedBufferStorage(buffers[3], static_cast<GLsizeiptr>(n * sizeof(glm::vec4)), surface_samples.data(),
                         0);
    glVertexArrayVertexBuffer(vao, 2, buffers[3], 0, sizeof(glm::vec4));
    glEnableVertexArrayAttrib(vao, 2);
    glVertexArrayAttribFormat(vao, 2, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 2, 2);
  }
  const Framebuffer target({1, 1});  // a surfaceless context has no default framebuffer to draw with
  target.bind();
  glUseProgram(program);
  uniforms.apply();
  glBindVertexArray(vao);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffers[2]);
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(n));
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);

  std::vector<glm::vec3> out(3 * n);
  glGetNamedBufferSubData(buffers[2], 0, static_cast<GLsizeiptr>(out.size() * sizeof(glm::vec3)), out.data());
  glUseProgram(0);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(4, buffers);
  glDeleteProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

  Captured captured;
  for (std::size_t i = 0; i < n; ++i) {
    captured.displaced.push_back(out[3 * i]);
    captured.perturbed.push_back(out[3 * i + 1]);
    captured.fragment_displaced.push_back(out[3 * i + 2]);
  }
  return captured;
}

// atan2 of |a x b| and a.b keeps its precision for small angles, where acos of a float does not (0.02 deg).
float angle_deg(glm::vec3 a, glm::vec3 b) {
  return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

// A bumpy sphere (normals not along the radius) under overlapping dents of different spreads.
struct DentedSphere : testing::Test {
  Mesh mesh = make_bumpy_sphere(40.0f, 2.0f, 60000);
  std::vector<Dent> dents{{{0.0f, -41.0f, 3.0f}, 4.0f, 5.0f},
                          {{6.0f, -40.0f, 8.0f}, 2.5f, 3.0f},
                          {{-10.0f, -35.0f, -15.0f}, 3.0f, 12.0f}};
  void SetUp() override { test::gl_context(); }
};

TEST_F(DentedSphere, DisplacedPositionsEqualTheCpuReference) {
  const Captured gpu = capture(mesh, dents);
  std::size_t moved = 0;
  float worst_relative = 0.0f, worst_displacement = 0.0f;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 v = mesh.positions_mm[i], n = glm::normalize(mesh.normals[i]);
    const glm::vec3 cpu = displaced_position(v, n, dents);
    worst_relative = std::max(worst_relative, glm::distance(gpu.displaced[i], cpu) / glm::length(cpu));
    // The fragment stage's own evaluation of the displacement, with which it lights the fragment.
    worst_relative =
        std::max(worst_relative, glm::distance(gpu.fragment_displaced[i], cpu) / glm::length(cpu));
    // The displacement itself, to the depth of the deepest dent: a stricter view than the position.
    worst_displacement = std::max(worst_displacement, glm::distance(gpu.displaced[i] - v, cpu - v) / 4.0f);
    if (glm::distance(cpu, v) > 1e-3f) ++moved;
  }
  EXPECT_LE(worst_relative, 1e-5f);
  EXPECT_LE(worst_displacement, 1e-5f);
  EXPECT_GT(moved, 500u);  // the dents do move a good many vertices
}

TEST_F(DentedSphere, PerturbedNormalsEqualTheCpuReference) {
  const Captured gpu = capture(mesh, dents);
  float worst = 0.0f, largest_tilt = 0.0f;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 cpu = perturbed_normal(glm::normalize(mesh.normals[i]), mesh.positions_mm[i], dents);
    EXPECT_NEAR(glm::length(gpu.perturbed[i]), 1.0f, 1e-5f);
    worst = std::max(worst, angle_deg(gpu.perturbed[i], cpu));
    largest_tilt = std::max(largest_tilt, angle_deg(cpu, mesh.normals[i]));
  }
  EXPECT_LE(worst, 1e-3f);
  EXPECT_GT(largest_tilt, 20.0f);
}

// The geodesic falloff on the GPU against the CPU: the first dent along the surface of the bumpy sphere
// (its bumps make the surface distance differ from the straight one), the others straight.
TEST_F(DentedSphere, AlongTheSurfaceTheGpuEqualsTheCpuReference) {
  SurfacePatch patch(mesh);
  patch.compute(-1, dents[0].center_mm, dent_cutoff_sigmas * dents[0].sigma_mm);
  std::vector<Dent> along = dents;
  along[0].along_surface = true;
  along[0].normal = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));  // pushed one way, not along each normal
  along[1].along_surface = true;  // only the first dent has a patch: a later one uses the straight line
  const Captured gpu = capture(mesh, along, max_dents, "450 core", patch.samples());
  float worst_displacement = 0.0f, worst_angle = 0.0f, largest_change = 0.0f;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 v = mesh.positions_mm[i], n = glm::normalize(mesh.normals[i]);
    const glm::vec4 sample = patch.samples()[i];
    const glm::vec3 cpu = displaced_position(v, n, along, sample);
    worst_displacement = std::max(worst_displacement, glm::distance(gpu.displaced[i], cpu) / 4.0f);
    worst_displacement = std::max(worst_displacement, glm::distance(gpu.fragment_displaced[i], cpu) / 4.0f);
    worst_angle = std::max(worst_angle, angle_deg(gpu.perturbed[i], perturbed_normal(n, v, along, sample)));
    largest_change = std::max(largest_change, glm::distance(cpu, displaced_position(v, n, dents)));
  }
  EXPECT_LE(worst_displacement, 1e-5f);
  EXPECT_LE(worst_angle, 2e-3f);
  EXPECT_GT(largest_change, 0.05f);  // the surface distance does change the dent here
}

// A wall that gives way further than the straight line's Gaussian would move it has a sample shorter than
// the straight line (SurfacePatch::PushedDent); both take it as it is. Here every sample of the patch is
// made 0.7 of its distance.
TEST_F(DentedSphere, ASampleShorterThanTheStraightLineIsTakenAsItIsOnBoth) {
  SurfacePatch patch(mesh);
  patch.compute(-1, dents[0].center_mm, dent_cutoff_sigmas * dents[0].sigma_mm);
  std::vector<glm::vec4> shorter(patch.samples().begin(), patch.samples().end());
  for (glm::vec4& sample : shorter)
    if (sample.w != surface_far_mm) sample.w *= 0.7f;
  Dent along = dents[0];
  along.along_surface = true;
  along.normal = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  const Captured gpu = capture(mesh, {&along, 1}, 1, "450 core", shorter);
  float worst_displacement = 0.0f, largest_change = 0.0f;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 v = mesh.positions_mm[i], n = glm::normalize(mesh.normals[i]);
    const glm::vec3 cpu = displaced_position(v, n, {&along, 1}, shorter[i]);
    worst_displacement = std::max(worst_displacement, glm::distance(gpu.displaced[i], cpu) / 4.0f);
    largest_change = std::max(largest_change,
                              glm::distance(cpu, displaced_position(v, n, {&along, 1}, patch.samples()[i])));
  }
  EXPECT_LE(worst_displacement, 1e-5f);
  EXPECT_GT(largest_change, 0.1f);  // the shorter samples move the vertices further
  std::printf("shorter samples: gpu against cpu %.2e, moved further by up to %.3f mm\n", worst_displacement,
              largest_change);
}

TEST_F(DentedSphere, FewerSlotsThanDentsIgnoreTheRest) {
  const Captured gpu = capture(mesh, dents, 1);
  const std::span<const Dent> first(dents.data(), 1);
  for (std::size_t i = 0; i < mesh.vertex_count(); i += 7) {
    const glm::vec3 v = mesh.positions_mm[i], n = glm::normalize(mesh.normals[i]);
    EXPECT_LE(glm::distance(gpu.displaced[i], displaced_position(v, n, first)), 1e-4f);
  }
}

TEST_F(DentedSphere, UpToMaxDentsSuperposeAndTheRestAreDropped) {
  std::vector<Dent> many;
  for (int i = 0; i < max_dents + 2; ++i) {
    many.push_back({{-40.0f + 8.0f * float(i), -39.0f, 0.0f}, 1.0f + 0.25f * float(i), 4.0f});
  }
  EXPECT_EQ(make_deform_block_data(many).count, max_dents);
  const Captured gpu = capture(mesh, many);
  const std::span<const Dent> kept(many.data(), max_dents);
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 v = mesh.positions_mm[i], n = glm::normalize(mesh.normals[i]);
    ASSERT_LE(glm::distance(gpu.displaced[i], displaced_position(v, n, kept)), 1e-4f) << "vertex " << i;
  }
}

// Each GLSL dialect gives the CPU reference's positions and normals: the same text, fed by the block or
// by the arrays.
void expect_dialect_matches_the_cpu(const std::string& version, GlslDialect dialect) {
  const std::string vertex = capture_vertex(version);
  EXPECT_EQ(dialect_of(vertex), dialect) << version;
  const Mesh mesh = make_bumpy_sphere(40.0f, 2.0f, 4000);
  const Dent dents[] = {{{0.0f, -41.0f, 3.0f}, 4.0f, 5.0f}, {{6.0f, -40.0f, 8.0f}, 2.5f, 3.0f}};
  const Captured gpu = capture(mesh, dents, 2, version);
  float worst_position = 0.0f, worst_angle = 0.0f;
  std::size_t moved = 0;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 v = mesh.positions_mm[i], n = glm::normalize(mesh.normals[i]);
    const glm::vec3 cpu = displaced_position(v, n, dents);
    worst_position = std::max(worst_position, glm::distance(gpu.displaced[i], cpu));
    worst_angle = std::max(worst_angle, angle_deg(gpu.perturbed[i], perturbed_normal(n, v, dents)));
    moved += glm::distance(cpu, v) > 1e-3f;
  }
  EXPECT_GT(moved, 50u) << version;
  EXPECT_LE(worst_position, 1e-4f) << version;
  EXPECT_LE(worst_angle, 1e-3f) << version;

  // The first dent along the surface, from each vertex's surface sample.
  SurfacePatch patch(mesh);
  patch.compute(-1, dents[0].center_mm, dent_cutoff_sigmas * dents[0].sigma_mm);
  Dent along[] = {dents[0], dents[1]};
  along[0].along_surface = true;
  along[0].normal = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  const Captured surface = capture(mesh, along, 2, version, patch.samples());
  worst_position = worst_angle = 0.0f;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::vec3 v = mesh.positions_mm[i], n = glm::normalize(mesh.normals[i]);
    const glm::vec4 sample = patch.samples()[i];
    worst_position = std::max(worst_position,
                              glm::distance(surface.displaced[i], displaced_position(v, n, along, sample)));
    worst_angle =
        std::max(worst_angle, angle_deg(surface.perturbed[i], perturbed_normal(n, v, along, sample)));
  }
  EXPECT_LE(worst_position, 1e-4f) << version << " along the surface";
  EXPECT_LE(worst_angle, 2e-3f) << version << " along the surface";
}

TEST(DeformGlslDialects, OldGlslTakesUniformArrays) {
  compatibility_context();
  for (const char* version : {"110", "120"})
    expect_dialect_matches_the_cpu(version, GlslDialect::uniform_arrays);
}

TEST(DeformGlslDialects, NewerGlslAndEsTakeTheUniformBlock) {
  test::gl_context();
  for (const char* version : {"140", "150", "330 core", "450 core", "300 es"}) {
    expect_dialect_matches_the_cpu(version, GlslDialect::uniform_block);
  }
}

TEST(DeformBlockLayout, MatchesTheDriversStd140Offsets) {
  test::gl_context();
  const ShaderProgram program("layout probe", insert_deform_glsl(capture_vertex("450 core")),
                              empty_fragment("450 core"));
  const GLuint block = glGetUniformBlockIndex(program.id(), deform_block_name);
  ASSERT_NE(block, GL_INVALID_INDEX);
  GLint size = 0;
  glGetActiveUniformBlockiv(program.id(), block, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
  EXPECT_EQ(static_cast<std::size_t>(size), sizeof(DeformBlockData));
  const char* names[] = {"palpate_dent_center_depth[0]", "palpate_dent_shape[0]", "palpate_dent_count",
                         "palpate_surface_dent"};
  GLuint indices[4] = {};
  glGetUniformIndices(program.id(), 4, names, indices);
  GLint offsets[4] = {};
  glGetActiveUniformsiv(program.id(), 4, indices, GL_UNIFORM_OFFSET, offsets);
  EXPECT_EQ(offsets[0], static_cast<GLint>(offsetof(DeformBlockData, center_depth)));
  EXPECT_EQ(offsets[1], static_cast<GLint>(offsetof(DeformBlockData, shape)));
  EXPECT_EQ(offsets[2], static_cast<GLint>(offsetof(DeformBlockData, count)));
  EXPECT_EQ(offsets[3], static_cast<GLint>(offsetof(DeformBlockData, surface_dent)));
  GLuint normal_index = 0;
  const char* normal_name = "palpate_surface_normal";
  glGetUniformIndices(program.id(), 1, &normal_name, &normal_index);
  GLint normal_offset = 0;
  glGetActiveUniformsiv(program.id(), 1, &normal_index, GL_UNIFORM_OFFSET, &normal_offset);
  EXPECT_EQ(normal_offset, static_cast<GLint>(offsetof(DeformBlockData, surface_normal)));
}

TEST(DeformBlockData, HoldsTheDerivedTermsOfEachDent) {
  const Dent dents[] = {{{1.0f, 2.0f, 3.0f}, 4.0f, 5.0f}};
  const DeformBlockData data = make_deform_block_data(dents);
  EXPECT_EQ(data.count, 1);
  EXPECT_EQ(data.center_depth[0], glm::vec4(1.0f, 2.0f, 3.0f, 4.0f));
  EXPECT_FLOAT_EQ(data.shape[0].x, 400.0f);        // (4 sigma)^2
  EXPECT_FLOAT_EQ(data.shape[0].y, 1.0f / 50.0f);  // 1 / (2 sigma^2)
  EXPECT_FLOAT_EQ(data.shape[0].z, 4.0f / 25.0f);  // p / sigma^2
  EXPECT_EQ(data.shape[1], glm::vec4(0.0f));       // unused slots reach nothing
}

TEST(InsertDeformGlsl, GoesAfterTheVersionExtensionAndPragmaLines) {
  const std::string source = insert_deform_glsl(
      "#version 120\n#extension GL_EXT_gpu_shader4 : enable\n// a comment\n#pragma optimize(on)\n\nattribute "
      "vec3 p;\nvoid main() {}\n");
  EXPECT_THAT(source,
              testing::StartsWith("#version 120\n#extension GL_EXT_gpu_shader4 : enable\n// a comment\n"
                                  "#pragma optimize(on)\n\n// palpate"));
  EXPECT_LT(source.find("uniform vec4 palpate_dent_center_depth"), source.find("attribute vec3 p"));
  EXPECT_EQ(source.find("PalpateDeform"), std::string::npos) << "GLSL 1.20 has no uniform blocks";
  EXPECT_THAT(source, testing::HasSubstr("#define PALPATE_DENT_SLOTS 8\n"));
  const std::string core = insert_deform_glsl("#version 330 core\nvoid main() {}\n", 2);
  EXPECT_THAT(core, testing::HasSubstr("layout(std140) uniform PalpateDeform"));
  EXPECT_THAT(core, testing::HasSubstr("#define PALPATE_DENT_SLOTS 2\n"));
  EXPECT_THAT(insert_deform_glsl("void main() {}", 2), testing::StartsWith("// palpate"));
  EXPECT_THAT(insert_deform_glsl("#version 300 es\nvoid main() {}\n"),
              testing::StartsWith("#version 300 es\nprecision highp float;\n"));
}

TEST(DeformUniforms, AProgramWithoutTheSnippetOrThatDidNotLinkIsAClearError) {
  test::gl_context();
  const ShaderProgram program("no deformation here",
                              "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n",
                              empty_fragment("450 core"));
  EXPECT_THAT(
      [&] { DeformUniforms uniforms(program.id()); },
      testing::ThrowsMessage<Error>(testing::HasSubstr("has neither the uniform block PalpateDeform")));
  // A program whose link failed (its vertex stage calls a function nobody defines).
  const GLuint broken = glCreateProgram();
  const GLuint vs = compile(GL_VERTEX_SHADER, "#version 450 core\nvoid f();\nvoid main() { f(); }\n");
  glAttachShader(broken, vs);
  glLinkProgram(broken);
  EXPECT_THAT([&] { DeformUniforms uniforms(broken); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("did not link")));
  glDeleteShader(vs);
  glDeleteProgram(broken);
}

}  // namespace
}  // namespace palpate::gl
