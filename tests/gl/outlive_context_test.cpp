// Hosts often end their context (glfwTerminate) before palpate's objects go out of scope: those objects'
// GL names went with the context, and destroying them afterwards must not call GL (the loader would
// abort: "Couldn't find current GLX or EGL context").
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <optional>

#include "gl_test_context.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/deform_glsl.hpp"
#include "palpate/gl/deform_uniforms.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/headless_context.hpp"
#include "palpate/gl/renderer.hpp"
#include "palpate/gl/shader_program.hpp"

namespace palpate::gl {
namespace {

TEST(OutlivingTheContext, DestroyingPalpatesGlObjectsAfterTheContextIsHarmless) {
  std::optional<ShaderProgram> program;
  std::optional<DeformUniforms> uniforms;
  std::optional<Framebuffer> target;
  std::optional<Renderer> renderer;
  {
    const HeadlessContext context;
    program.emplace("outlives its context",
                    insert_deform_glsl("#version 330 core\nin vec3 p;\n"
                                       "void main() { gl_Position = vec4(palpate_displace(p, p), 1.0); }\n",
                                       1),
                    "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
    uniforms.emplace(program->id());
    ASSERT_NE(uniforms->buffer(), 0u);
    target.emplace(FramebufferParams{64, 64});
    target->bind();
    renderer.emplace();
    Scene scene;
    scene.objects.emplace_back().mesh = make_sphere(50.0f, 500);
    renderer->upload(scene);
    const ObjectDent dent{0, {{0, -50, 0}, 5.0f, 7.0f}};
    const DrawResult drawn =
        renderer->draw(glm::lookAt(glm::vec3(0, -200, 0), glm::vec3(0), glm::vec3(0, 0, 1)),
                       glm::perspective(0.7f, 1.0f, 10.0f, 500.0f), {&dent, 1});
    ASSERT_FALSE(drawn.drew_nothing());
  }  // the context ends here, with no other current
  renderer.reset();
  target.reset();
  uniforms.reset();
  program.reset();
  test::gl_context();  // the shared test context is still usable
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace palpate::gl
