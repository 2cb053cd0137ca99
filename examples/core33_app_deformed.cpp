// An OpenGL 3.3 core application with its own loader (libepoxy) and its own window (GLFW), shaders,
// framebuffer and buffers: none of palpate's GL classes. core33_app.cpp is the program as it was,
// core33_app_deformed.cpp the same with palpate's deformation (README.md shows the diff).
// Usage: core33_app [--headless OUT.png] [--mesh FILE.ply]   (the mesh in millimetres)
#include <epoxy/gl.h>
// epoxy before GLFW, so that GLFW does not include GL/gl.h.
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

#include "palpate/core/load.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/deform_uniforms.hpp"
#include "palpate/gl/png.hpp"

const char* vertex_source = R"glsl(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 view_projection;
out vec3 world_normal;
out vec3 rest_world;
void main() {
  vec3 world = (model * vec4(position, 1.0)).xyz;
  world_normal = mat3(model) * normal;
  rest_world = world;
  gl_Position = view_projection * vec4(palpate_displace(world, normalize(world_normal)), 1.0);
}
)glsl";

const char* fragment_source = R"glsl(#version 330 core
in vec3 world_normal;
in vec3 rest_world;
out vec4 color;
void main() {
  vec3 n = palpate_perturb_normal(normalize(world_normal), rest_world);
  float light = max(dot(n, normalize(vec3(-0.6, -0.5, 0.6))), 0.0);
  color = vec4(vec3(0.08) + vec3(0.9, 0.72, 0.62) * light, 1.0);
}
)glsl";

GLuint compile(GLenum stage, const std::string& source) {
  const GLuint shader = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    std::fprintf(stderr, "shader: %s\n", log);
  }
  return shader;
}

int main(int argc, char** argv) {
  const char* headless = nullptr;
  const char* mesh_file = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--headless") == 0) headless = argv[i + 1];
    if (std::strcmp(argv[i], "--mesh") == 0) mesh_file = argv[i + 1];
  }
  constexpr int width = 800, height = 800;
  if (!glfwInit()) return 1;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_VISIBLE, headless ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, "core 3.3 app", nullptr, nullptr);
  if (!window) return 1;
  glfwMakeContextCurrent(window);

  const palpate::Mesh mesh = mesh_file ? palpate::load_mesh(mesh_file) : palpate::make_sphere(50.0f, 40000);
  GLuint vertex_array = 0, buffers[3];
  glGenVertexArrays(1, &vertex_array);
  glBindVertexArray(vertex_array);
  glGenBuffers(3, buffers);
  const std::vector<glm::vec3>* attributes[] = {&mesh.positions_mm, &mesh.normals};
  for (GLuint attribute = 0; attribute < 2; ++attribute) {
    glBindBuffer(GL_ARRAY_BUFFER, buffers[attribute]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(attributes[attribute]->size() * sizeof(glm::vec3)),
                 attributes[attribute]->data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(attribute);
    glVertexAttribPointer(attribute, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[2]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);

  const GLuint program = glCreateProgram();
  glAttachShader(program, compile(GL_VERTEX_SHADER, palpate::gl::insert_deform_glsl(vertex_source, 1)));
  glAttachShader(program, compile(GL_FRAGMENT_SHADER, palpate::gl::insert_deform_glsl(fragment_source, 1)));
  glLinkProgram(program);
  palpate::gl::DeformUniforms dents(program);

  const glm::mat4 view_projection =
      glm::perspective(glm::radians(40.0f), float(width) / height, 10.0f, 500.0f) *
      glm::lookAt(glm::vec3(0, -170, 40), glm::vec3(0), glm::vec3(0, 0, 1));
  const auto draw_frame = [&](double time_s) {
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const glm::mat4 model = glm::rotate(glm::mat4(1.0f), float(0.3 * time_s), glm::vec3(0, 0, 1));
    const palpate::Dent dent{glm::normalize(glm::vec3(0.2f, -1.0f, 0.35f)) * 50.0f, 5.0f, 7.0f};  // world mm
    dents.set({&dent, 1});
    glUseProgram(program);
    dents.apply();
    glUniformMatrix4fv(glGetUniformLocation(program, "model"), 1, GL_FALSE, glm::value_ptr(model));
    glUniformMatrix4fv(glGetUniformLocation(program, "view_projection"), 1, GL_FALSE,
                       glm::value_ptr(view_projection));
    glBindVertexArray(vertex_array);
    glDrawElements(GL_TRIANGLES, GLsizei(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
  };

  if (headless) {  // into a framebuffer of its own, read back
    GLuint framebuffer = 0, renderbuffers[2];
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glGenRenderbuffers(2, renderbuffers);
    const GLenum formats[] = {GL_RGBA8, GL_DEPTH_COMPONENT24},
                 points[] = {GL_COLOR_ATTACHMENT0, GL_DEPTH_ATTACHMENT};
    for (int i = 0; i < 2; ++i) {
      glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[i]);
      glRenderbufferStorage(GL_RENDERBUFFER, formats[i], width, height);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, points[i], GL_RENDERBUFFER, renderbuffers[i]);
    }
    glViewport(0, 0, width, height);
    draw_frame(0.0);
    std::vector<std::uint8_t> pixels(std::size_t(width) * height * 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    palpate::gl::save_png(headless, width, height, pixels);
    std::printf("wrote %s\n", headless);
  } else {
    for (double t = 0.0; !glfwWindowShouldClose(window); t += 1.0 / 60.0) {
      int w = 0, h = 0;
      glfwGetFramebufferSize(window, &w, &h);
      glViewport(0, 0, w, h);
      draw_frame(t);
      glfwSwapBuffers(window);
      glfwPollEvents();
    }
  }
  glfwTerminate();
  return 0;
}
