// Stereo on llvmpipe: a point drawn at a known depth lands in the two eyes' pictures with the
// parallax that similar triangles predict (worked out here, not by StereoCamera), none at the
// convergence distance; the anaglyph's channels are Dubois' combinations of the two pictures; the
// mirrored picture is the mono one flipped, pixel for pixel; the caller's state is left as found.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "gl_test_context.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/renderer.hpp"
#include "palpate/gl/stereo_compositor.hpp"

namespace palpate::gl {
namespace {

constexpr float fov_y = 0.7f, convergence = 500.0f, separation = 63.0f;

// The mono camera: at (0, -500, 0), looking at the origin along +y, z up.
MonoCamera mono(float aspect) {
  return {glm::lookAt(glm::vec3(0, -500, 0), glm::vec3(0), glm::vec3(0, 0, 1)), fov_y, aspect, 10.0f,
          5000.0f};
}

// A small ball whose centre is `depth` straight ahead of the camera and `right` to its right.
Scene ball_at(float depth, float right) {
  Scene scene;
  SceneObject ball;
  ball.name = "ball";
  ball.mesh = make_sphere(5.0f, 2000);
  ball.transform = glm::translate(glm::mat4(1.0f), glm::vec3(right, depth - 500.0f, 0.0f));
  scene.objects.push_back(std::move(ball));
  return scene;
}

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // bottom row first
  const std::uint8_t* at(int x, int y) const {
    return &rgba[4 * (std::size_t(y) * std::size_t(width) + std::size_t(x))];
  }
};

// Renders through the compositor into a fresh output and reads it back.
Image composite(StereoMode mode, Mirror mirror, int width, int height,
                const std::function<void(const EyeTarget&)>& draw_eye) {
  test::gl_context();
  const Framebuffer output({width, height});
  output.bind();
  StereoCompositor compositor;
  compositor.render(mode, mirror, width, height, draw_eye);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  return {width, height, output.read_rgba8()};
}

// The scene drawn for each eye with StereoCamera's matrices.
Image stereo_frame(const Scene& scene, StereoMode mode, Mirror mirror, int width, int height) {
  test::gl_context();
  Renderer renderer;
  renderer.upload(scene);
  StereoCamera stereo;
  stereo.eye_separation_mm = separation;
  stereo.convergence_mm = convergence;
  return composite(mode, mirror, width, height, [&](const EyeTarget& target) {
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const EyeView eye = stereo.eye(target.eye, mono(target.aspect));
    renderer.draw(eye.view, eye.projection, std::span<const ObjectDent>(), {});
  });
}

// The centroid of the lit pixels in the rectangle [x0, x0 + w) x [y0, y0 + h), relative to its corner.
glm::dvec2 centroid(const Image& image, int x0, int y0, int w, int h) {
  glm::dvec2 sum(0.0);
  double count = 0.0;
  for (int y = y0; y < y0 + h; ++y) {
    for (int x = x0; x < x0 + w; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (p[0] + p[1] + p[2] > 30) {
        sum += glm::dvec2(x - x0 + 0.5, y - y0 + 0.5);
        count += 1.0;
      }
    }
  }
  EXPECT_GT(count, 4.0) << "the ball is not in view";
  return count > 0.0 ? sum / count : glm::dvec2(-1.0);
}

// Where the ball's centre lands in an eye's picture of `eye_width` pixels: the ray from the eye at
// x = +-separation / 2 to the point (right, -depth) meets the screen at z = -convergence at
// x = eye + (right - eye) convergence / depth; the screen is 2 aspect convergence tan(fov / 2) wide.
double predicted_column(double eye_x, float depth, float right, float aspect, int eye_width) {
  const double on_screen = eye_x + (right - eye_x) * convergence / depth;
  const double half_width = aspect * convergence * std::tan(0.5 * fov_y);
  return (on_screen / half_width + 1.0) * 0.5 * eye_width;
}

TEST(Stereo, SideBySideParallaxIsWhatTheEyesGeometryPredicts) {
  constexpr int width = 800, height = 400;
  const float aspect = float(width) / height;  // each eye squeezed into its half
  for (const float depth : {300.0f, 500.0f, 1000.0f}) {
    const Image image =
        stereo_frame(ball_at(depth, 20.0f), StereoMode::side_by_side, Mirror::none, width, height);
    const glm::dvec2 left = centroid(image, 0, 0, width / 2, height);
    const glm::dvec2 right = centroid(image, width / 2, 0, width / 2, height);
    const double expected_left = predicted_column(-0.5 * separation, depth, 20.0f, aspect, width / 2);
    const double expected_right = predicted_column(0.5 * separation, depth, 20.0f, aspect, width / 2);
    std::printf(
        "depth %4.0f mm: parallax %+7.3f px (predicted %+7.3f), columns %.2f / %.2f (predicted %.2f / "
        "%.2f)\n",
        depth, right.x - left.x, expected_right - expected_left, left.x, right.x, expected_left,
        expected_right);
    EXPECT_NEAR(left.x, expected_left, 1.0);
    EXPECT_NEAR(right.x, expected_right, 1.0);
    EXPECT_NEAR(right.x - left.x, expected_right - expected_left, 1.0);
    EXPECT_NEAR(right.y, left.y, 0.25) << "vertical parallax";
    if (depth == convergence) {
      EXPECT_NEAR(right.x - left.x, 0.0, 0.25) << "parallax at the convergence distance";
    }
  }
}

TEST(Stereo, TopBottomPutsTheLeftEyeOnTopWithTheSameParallax) {
  constexpr int width = 400, height = 400;
  const float aspect = 1.0f;
  const Image image =
      stereo_frame(ball_at(1000.0f, 0.0f), StereoMode::top_bottom, Mirror::none, width, height);
  const glm::dvec2 left = centroid(image, 0, height / 2, width, height / 2);  // rows are bottom first
  const glm::dvec2 right = centroid(image, 0, 0, width, height / 2);
  EXPECT_NEAR(right.x - left.x,
              predicted_column(0.5 * separation, 1000.0f, 0.0f, aspect, width) -
                  predicted_column(-0.5 * separation, 1000.0f, 0.0f, aspect, width),
              1.0);
  EXPECT_GT(right.x - left.x, 10.0);  // behind the screen: the right eye sees it further right
  EXPECT_NEAR(right.y, left.y, 0.25);
}

TEST(Stereo, AnaglyphChannelsAreDuboisCombinationsOfTheTwoPictures) {
  constexpr int width = 96, height = 64;
  // Each eye: a plain colour with a rectangle of another, in different places, so that every pairing
  // of the four colours occurs (saturated ones too, where the matrices' sums clamp).
  // Multiples of 1/5 are exact in 8 bits (k * 51 / 255).
  const glm::vec3 left_back(0.2f, 0.8f, 0.4f), left_box(1.0f, 0.2f, 0.6f);
  const glm::vec3 right_back(0.6f, 0.4f, 0.2f), right_box(0.0f, 1.0f, 1.0f);
  const auto paint = [](glm::vec3 back, glm::vec3 box, int x0) {
    glClearColor(back.r, back.g, back.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x0, 16, 40, 32);
    glClearColor(box.r, box.g, box.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
  };
  const Image image =
      composite(StereoMode::anaglyph, Mirror::none, width, height, [&](const EyeTarget& target) {
        if (target.eye == Eye::left) paint(left_back, left_box, 8);
        if (target.eye == Eye::right) paint(right_back, right_box, 40);
      });
  int checked = 0;
  double worst = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const bool in_row = y >= 16 && y < 48;
      const glm::vec3 l = (in_row && x >= 8 && x < 48 ? left_box : left_back);
      const glm::vec3 r = (in_row && x >= 40 && x < 80 ? right_box : right_back);
      for (int channel = 0; channel < 3; ++channel) {
        double expected = 0.0;
        for (int k = 0; k < 3; ++k)
          expected += dubois_left[std::size_t(3 * channel + k)] * l[k] +
                      dubois_right[std::size_t(3 * channel + k)] * r[k];
        expected = std::clamp(expected, 0.0, 1.0);
        worst = std::max(worst, std::abs(image.at(x, y)[channel] / 255.0 - expected));
      }
      ++checked;
    }
  }
  std::printf("anaglyph: %d pixels, largest channel error %.4f (1/255 = %.4f)\n", checked, worst,
              1.0 / 255.0);
  EXPECT_LE(worst, 0.6 / 255.0);  // the 8-bit output's rounding
}

TEST(Stereo, MirroredIsTheMonoPictureFlipped) {
  constexpr int width = 320, height = 240;
  const Scene scene = ball_at(500.0f, 45.0f);  // off centre, so a flip shows
  const Image plain = stereo_frame(scene, StereoMode::mono, Mirror::none, width, height);
  const Image across = stereo_frame(scene, StereoMode::mono, Mirror::horizontal, width, height);
  const Image upside = stereo_frame(scene, StereoMode::mono, Mirror::vertical, width, height);
  int lit = 0, differ_across = 0, differ_upside = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      lit += plain.at(x, y)[0] > 10;
      for (int c = 0; c < 4; ++c) {
        differ_across += across.at(x, y)[c] != plain.at(width - 1 - x, y)[c];
        differ_upside += upside.at(x, y)[c] != plain.at(x, height - 1 - y)[c];
      }
    }
  }
  EXPECT_GT(lit, 20);
  EXPECT_EQ(differ_across, 0);
  EXPECT_EQ(differ_upside, 0);
  EXPECT_NE(centroid(plain, 0, 0, width, height).x, centroid(across, 0, 0, width, height).x);
}

TEST(Stereo, MonoThroughTheCompositorIsTheDirectDraw) {
  constexpr int width = 160, height = 120;
  const Scene scene = ball_at(400.0f, -30.0f);
  const Image through = stereo_frame(scene, StereoMode::mono, Mirror::none, width, height);
  test::gl_context();
  const Framebuffer direct({width, height});
  direct.bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  Renderer renderer;
  renderer.upload(scene);
  const EyeView eye = StereoCamera{}.eye(Eye::centre, mono(float(width) / height));
  renderer.draw(eye.view, eye.projection, std::span<const ObjectDent>(), {});
  EXPECT_EQ(direct.read_rgba8(), through.rgba);
}

TEST(Stereo, LeavesTheCallersStateAsFoundAndRefusesQuadBuffersWithoutThem) {
  test::gl_context();
  const Framebuffer output({64, 48});
  output.bind();
  glViewport(3, 4, 50, 40);
  glEnable(GL_SCISSOR_TEST);
  glEnable(GL_DEPTH_TEST);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_TRUE);
  GLuint host_textures[2] = {};
  glGenTextures(2, host_textures);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, host_textures[0]);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, host_textures[1]);
  StereoCompositor compositor;
  compositor.render(StereoMode::anaglyph, Mirror::vertical, 64, 48, [](const EyeTarget&) {});
  GLint framebuffer = 0, viewport[4] = {}, active = 0;
  GLboolean mask[4] = {};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glGetIntegerv(GL_VIEWPORT, viewport);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
  glGetBooleanv(GL_COLOR_WRITEMASK, mask);
  EXPECT_EQ(GLuint(framebuffer), output.id());
  EXPECT_EQ(viewport[0], 3);
  EXPECT_EQ(viewport[3], 40);
  EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
  EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
  EXPECT_EQ(mask[1], GL_FALSE);
  EXPECT_EQ(active, GL_TEXTURE1);
  for (int unit = 0; unit < 2; ++unit) {
    GLint texture = 0;
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &texture);
    EXPECT_EQ(GLuint(texture), host_textures[unit]) << "texture unit " << unit;
  }
  EXPECT_FALSE(StereoCompositor::stereo_buffers_available());
  try {
    compositor.render(StereoMode::quad_buffer, Mirror::none, 64, 48, [](const EyeTarget&) {});
    ADD_FAILURE() << "quad_buffer rendered without stereo buffers";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("quad-buffered stereo"), std::string::npos) << error.what();
  }
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glActiveTexture(GL_TEXTURE0);
  glDeleteTextures(2, host_textures);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

}  // namespace
}  // namespace palpate::gl
