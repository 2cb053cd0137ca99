// An OpenGL 4.5 application that draws a mesh with its own shaders, in a window or, with --headless FILE,
// offscreen into a PNG, using palpate's own context, window, framebuffer and shader classes.
// gl45_app.cpp is the application as it was, gl45_app_deformed.cpp the same with palpate's GPU
// deformation added (README.md shows the diff).
// Usage: gl45_app [--headless OUT.png] [--mesh FILE.ply]
#include <epoxy/gl.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <optional>

#include "palpate/core/load.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/png.hpp"
#include "palpate/gl/shader_program.hpp"
#include "palpate/gl/window.hpp"

constexpr const char* vertex_source = R"glsl(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 view_projection;
out vec3 world_normal;
void main() {
  vec3 world = (model * vec4(position, 1.0)).xyz;
  world_normal = mat3(model) * normal;
  gl_Position = view_projection * vec4(world, 1.0);
}
)glsl";

constexpr const char* fragment_source = R"glsl(#version 450 core
in vec3 world_normal;
out vec4 color;
void main() {
  vec3 n = normalize(world_normal);
  float light = max(dot(n, normalize(vec3(-0.6, -0.5, 0.6))), 0.0);
  color = vec4(vec3(0.08) + vec3(0.9, 0.72, 0.62) * light, 1.0);
}
)glsl";

int main(int argc, char** argv) {
  const char* headless = nullptr;
  const char* mesh_file = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--headless") == 0) headless = argv[i + 1];
    if (std::strcmp(argv[i], "--mesh") == 0) mesh_file = argv[i + 1];
  }
  constexpr int width = 800, height = 800;
  std::optional<palpate::gl::HeadlessContext> context;
  std::optional<palpate::gl::Window> window;
  if (headless) {
    context.emplace();
  } else {
    window.emplace(palpate::gl::WindowParams{width, height, "existing app"});
  }

  const palpate::Mesh mesh = mesh_file ? palpate::load_mesh(mesh_file) : palpate::make_sphere(50.0f, 40000);
  GLuint vertex_array = 0, buffers[3] = {};
  glCreateVertexArrays(1, &vertex_array);
  glCreateBuffers(3, buffers);
  glNamedBufferStorage(buffers[0], GLsizeiptr(mesh.positions_mm.size() * sizeof(glm::vec3)),
                       mesh.positions_mm.data(), 0);
  glNamedBufferStorage(buffers[1], GLsizeiptr(mesh.normals.size() * sizeof(glm::vec3)), mesh.normals.data(),
                       0);
  glNamedBufferStorage(buffers[2], GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                       mesh.indices.data(), 0);
  for (GLuint attribute = 0; attribute < 2; ++attribute) {
    glVertexArrayVertexBuffer(vertex_array, attribute, buffers[attribute], 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(vertex_array, attribute);
    glVertexArrayAttribFormat(vertex_array, attribute, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vertex_array, attribute, attribute);
  }
  glVertexArrayElementBuffer(vertex_array, buffers[2]);
  const palpate::gl::ShaderProgram program("existing app", vertex_source, fragment_source);

  const glm::mat4 view_projection =
      glm::perspective(glm::radians(40.0f), float(width) / float(height), 10.0f, 500.0f) *
      glm::lookAt(glm::vec3(0, -170, 40), glm::vec3(0), glm::vec3(0, 0, 1));
  const auto draw_frame = [&](double time_s) {
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const glm::mat4 model = glm::rotate(glm::mat4(1.0f), float(0.3 * time_s), glm::vec3(0, 0, 1));
    glUseProgram(program.id());
    glUniformMatrix4fv(program.uniform("model"), 1, GL_FALSE, glm::value_ptr(model));
    glUniformMatrix4fv(program.uniform("view_projection"), 1, GL_FALSE, glm::value_ptr(view_projection));
    glBindVertexArray(vertex_array);
    glDrawElements(GL_TRIANGLES, GLsizei(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
  };

  if (headless) {
    const palpate::gl::Framebuffer target({width, height});
    target.bind();
    draw_frame(0.0);
    palpate::gl::save_png(headless, width, height, target.read_rgba8());
    std::printf("wrote %s\n", headless);
  } else {
    for (double t = 0.0; !window->should_close(); t += 1.0 / 60.0) {
      glViewport(0, 0, window->framebuffer_width(), window->framebuffer_height());
      draw_frame(t);
      window->swap_buffers();
      palpate::gl::Window::poll_events();
    }
  }
  glDeleteBuffers(3, buffers);
  glDeleteVertexArrays(1, &vertex_array);
  return 0;
}
