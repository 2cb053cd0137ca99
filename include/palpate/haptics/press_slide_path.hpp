#pragma once
// A scripted tool-tip path aimed at a point of a surface: approach along the normal, press to a depth,
// slide along the surface with the depth varying, pull out, rest. Evaluated analytically (no samples):
// sample() is noexcept and allocation-free, so a ScriptedDevice can call it in the haptic tick.
//
// The surface is taken as the plane through the point (curvature_radius_mm = 0) or as the convex
// sphere of that radius touching it there (centre = point - normal * radius), so a slide follows a
// curved object instead of leaving it. Depth is measured along that surface's normal, positive inside.
#include <glm/vec3.hpp>

#include "palpate/core/scene.hpp"
#include "palpate/haptics/device.hpp"

namespace palpate {

struct PressSlideParams {
  glm::vec3 surface_point_mm{0.0f};             // where the approach lands, device frame
  glm::vec3 normal{0.0f, 0.0f, 1.0f};           // outward surface normal there (normalised on use)
  glm::vec3 slide_direction{1.0f, 0.0f, 0.0f};  // projected onto the tangent plane; not along the normal
  float curvature_radius_mm = 0.0f;             // 0: flat; > 0: convex sphere of this radius
  float start_height_mm = 20.0f;                // start (and end) this far outside the surface
  float approach_speed_mm_per_s = 25.0f;
  float press_depth_mm = 2.5f;         // depth when the slide begins (negative: hover above)
  float slide_length_mm = 52.0f;       // arc length on the surface
  float slide_speed_mm_per_s = 25.0f;  // along the surface
  float depth_amplitude_mm = 1.5f;     // depth = press + amplitude * sin(2 pi cycles s / length)
  float depth_cycles = 1.0f;
  float retract_speed_mm_per_s = 25.0f;
  float rest_s = 0.0f;  // hold at the end, start_height_mm outside
};

class PressSlidePath {
 public:
  // Throws palpate::Error naming the field for non-finite values, non-positive speeds or lengths,
  // a zero normal, a slide direction along the normal, or a start height not above the press depth.
  explicit PressSlidePath(const PressSlideParams& spec);

  // Position and velocity at `time_s` (clamped to [0, duration]); buttons are 0.
  DeviceState sample(double time_s) const noexcept;

  double approach_end_s() const noexcept { return approach_end_s_; }  // the slide begins
  double slide_end_s() const noexcept { return slide_end_s_; }        // the pull-out begins
  double retract_end_s() const noexcept { return retract_end_s_; }    // back at start height
  double start_s() const noexcept { return 0.0; }
  double end_s() const noexcept { return duration_s_; }
  double duration_s() const noexcept { return duration_s_; }

  // Depth below the surface at slide arc length `s_mm` (0 at the slide's start).
  float depth_at(float s_mm) const noexcept;
  // Surface point and outward normal at slide arc length `s_mm`.
  glm::vec3 surface_at(float s_mm) const noexcept;
  glm::vec3 normal_at(float s_mm) const noexcept;
  const PressSlideParams& spec() const noexcept { return spec_; }

 private:
  PressSlideParams spec_;
  glm::vec3 normal_{0.0f}, tangent_{0.0f};
  double approach_end_s_ = 0, slide_end_s_ = 0, retract_end_s_ = 0, duration_s_ = 0;
};

// `spec` aimed at vertex `vertex` of `object`, in world (scene) coordinates: the surface point is the
// vertex, the normal the mean of the vertex normals within `smoothing_radius_mm` (the surface's
// direction at the scale of a slide, not one bump's), the curvature that of the sphere through the
// vertex about the object's bounds centre where that normal points away from the centre (within 45
// degrees) and the sphere is more than twice the deepest press in radius, else flat. The other fields
// are kept. Allocates when the mesh has
// no normals; throws palpate::Error for a vertex out of range.
PressSlideParams aim_press_slide(const SceneObject& object, std::size_t vertex, glm::vec3 slide_direction,
                                 PressSlideParams spec = {}, float smoothing_radius_mm = 8.0f);

}  // namespace palpate
