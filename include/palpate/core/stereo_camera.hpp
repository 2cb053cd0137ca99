#pragma once
// Stereo views for a head in front of a screen: each eye gets its own view and an off-axis
// (asymmetric) frustum through one shared screen rectangle, so the eyes look in parallel and the
// picture has no vertical parallax (no toe-in). The screen is the mono camera's field of view at the
// convergence distance: a point there lands on the same pixel for both eyes (zero parallax), a point
// behind it shifts right in the right eye (positive parallax), a point in front of it left.
//
// A tracked head moves the eyes and not the screen (Kooima, "Generalized Perspective Projection",
// 2008): head_mm is the head's offset from where the mono camera sits, in that camera's frame (x right,
// y up, z toward the viewer, mm), so leaning right shows more of an object's right side while what lies
// in the screen plane stays put.
//
// Lengths are in the view's world units (palpate's are mm; an application in metres gives metres).
// Any host camera works: give its view matrix, vertical field of view, aspect and clip planes. Pure
// math (no GL): an application on any OpenGL draws each eye with these matrices into its own viewport
// or back buffer; gl::StereoCompositor does the combining for palpate's own windows.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "palpate/core/orbit_camera.hpp"

namespace palpate {

enum class Eye { left, right, centre };  // centre: the head itself (a mono view that follows the head)

struct EyeView {
  glm::mat4 view{1.0f}, projection{1.0f};
  glm::vec3 position_mm{0.0f};  // the eye, world mm
};

// The mono camera a stereo pair is made from.
struct MonoCamera {
  glm::mat4 view{1.0f};  // world to camera (right-handed, looking down -z)
  float fov_y_rad = 0.7f;
  float aspect = 1.0f;  // width / height of the picture each eye fills
  float near_mm = 1.0f, far_mm = 1000.0f;
};
MonoCamera mono_camera(const OrbitCamera& camera, float aspect) noexcept;  // its projection's planes

struct StereoCamera {
  float eye_separation_mm = 63.0f;  // between the pupils (an adult's mean; 54-74 mm)
  float convergence_mm = 500.0f;    // from the head to the screen (the plane of zero parallax), > 0
  glm::vec3 head_mm{0.0f};          // the tracked head's offset, in the mono camera's frame

  // The eye's view and off-axis projection. The eye is kept in front of the screen (at least 1% of
  // the convergence distance), so a head tracker's glitch never turns the frustum inside out.
  EyeView eye(Eye which, const MonoCamera& mono) const noexcept;

  // Where on the screen plane (mm, right minus left eye) a point straight ahead of a centred head at
  // `depth_mm` from it appears: eye_separation * (1 - convergence / depth).
  float screen_parallax_mm(float depth_mm) const noexcept;
};

}  // namespace palpate
