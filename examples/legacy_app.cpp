// An OpenGL 2.1 application in the style of many haptics frameworks: a GLFW window, GLEW as its loader,
// fixed-function matrices, GLSL 1.20 shaders that use gl_ModelViewMatrix and generic attributes,
// vertex data uploaded as doubles, and units in metres. Built with a plain Makefile (pkg-config).
// legacy_app.cpp is the program as it was; legacy_app_deformed.cpp the same with palpate's
// deformation (README.md shows the diff).
// Usage: legacy_app [--headless OUT.png] [--mesh FILE.ply]   (the mesh in millimetres)
#include <GL/glew.h>
// GLEW before GLFW, as GLEW wants.
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

#include "palpate/core/load.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/png.hpp"

const char* vertex_source = R"glsl(#version 120
attribute vec3 position;
attribute vec3 normal;
varying vec3 eye_normal;
void main() {
  eye_normal = gl_NormalMatrix * normal;
  gl_Position = gl_ModelViewProjectionMatrix * vec4(position, 1.0);
}
)glsl";

const char* fragment_source = R"glsl(#version 120
varying vec3 eye_normal;
uniform vec3 light_eye;  // toward the light, eye space
void main() {
  vec3 n = normalize(eye_normal);
  gl_FragColor = vec4(vec3(0.08) + vec3(0.9, 0.72, 0.62) * max(dot(n, light_eye), 0.0), 1.0);
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
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
  glfwWindowHint(GLFW_VISIBLE, headless ? GLFW_FALSE : GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, "legacy app", nullptr, nullptr);
  if (!window) return 1;
  glfwMakeContextCurrent(window);
  if (glewInit() != GLEW_OK) return 1;

  // The mesh in metres, as doubles.
  const palpate::Mesh mesh = mesh_file ? palpate::load_mesh(mesh_file) : palpate::make_sphere(50.0f, 40000);
  std::vector<double> positions, normals;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    for (int k = 0; k < 3; ++k) {
      positions.push_back(1e-3 * mesh.positions_mm[v][k]);
      normals.push_back(mesh.normals[v][k]);
    }
  }
  GLuint buffers[3];
  glGenBuffers(3, buffers);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(positions.size() * sizeof(double)), positions.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[1]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(normals.size() * sizeof(double)), normals.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers[2]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);

  const GLuint program = glCreateProgram();
  glAttachShader(program, compile(GL_VERTEX_SHADER, vertex_source));
  glAttachShader(program, compile(GL_FRAGMENT_SHADER, fragment_source));
  glBindAttribLocation(program, 0, "position");
  glBindAttribLocation(program, 1, "normal");
  glLinkProgram(program);

  const glm::dmat4 projection = glm::perspective(glm::radians(40.0), double(width) / height, 0.01, 0.5);
  const glm::dmat4 view = glm::lookAt(glm::dvec3(0, -0.17, 0.04), glm::dvec3(0), glm::dvec3(0, 0, 1));
  const glm::vec3 light_eye = glm::normalize(glm::mat3(view) * glm::vec3(-0.6f, -0.5f, 0.6f));
  const auto draw_frame = [&](double time_s) {
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_CULL_FACE);
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(glm::value_ptr(projection));
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixd(glm::value_ptr(view * glm::rotate(glm::dmat4(1.0), 0.3 * time_s, glm::dvec3(0, 0, 1))));
    glUseProgram(program);
    glUniform3fv(glGetUniformLocation(program, "light_eye"), 1, glm::value_ptr(light_eye));
    for (GLuint attribute = 0; attribute < 2; ++attribute) {
      glBindBuffer(GL_ARRAY_BUFFER, buffers[attribute]);
      glEnableVertexAttribArray(attribute);
      glVertexAttribPointer(attribute, 3, GL_DOUBLE, GL_FALSE, 0, nullptr);
    }
    glDrawElements(GL_TRIANGLES, GLsizei(mesh.indices.size()), GL_UNSIGNED_INT, nullptr);
  };

  if (headless) {
    glViewport(0, 0, width, height);
    draw_frame(0.0);
    std::vector<std::uint8_t> pixels(std::size_t(width) * height * 4);
    glReadBuffer(GL_BACK);
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
