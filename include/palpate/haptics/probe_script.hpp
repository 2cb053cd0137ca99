#pragma once
// Scripted probe paths on a real scene, for demos, benchmarks and tests of a whole application: presses
// aimed at what a camera sees, presses strung into one path, and slides that follow the real surface.
// Each gives a SampledPath (1 ms samples, scene mm) for a ScriptedDevice with the identity transform.
// Setup code: allocates and throws palpate::Error.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/orbit_camera.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/press_slide_path.hpp"
#include "palpate/haptics/sampled_path.hpp"

namespace palpate {

// A path and the strokes on it.
struct ProbeScript {
  struct Stroke {
    double start_s = 0.0, end_s = 0.0;  // from the start of the approach to the end of the pull-out
    bool slide = false;                 // a long slide (else a press)
  };
  SampledPath path{{PathSample{}}};
  std::vector<Stroke> strokes;
};

// Presses one after the other, with transits between them that leave along the normal to
// `clearance_mm` so that the tip never cuts through the object in free flight.
ProbeScript press_script(std::span<const PressSlideParams> presses, float clearance_mm = 60.0f);

// Presses at the points of object `object` that the camera sees through the pixels `sites_px` of a
// viewport of `viewport_px` pixels, each sliding toward the camera's right: `params` aimed (see
// aim_press_slide) at the vertex of the hit triangle nearest the hit. `bvh` must hold the object (it
// may hold others: they neither hide nor are aimed at). Throws naming the site when its ray misses.
std::vector<PressSlideParams> aim_at_view(const Scene& scene, const Bvh& bvh, int object,
                                          const OrbitCamera& camera, std::span<const glm::vec2> sites_px,
                                          glm::vec2 viewport_px, const PressSlideParams& params);

struct SurfaceSlideParams {
  float start_height_mm = 12.0f;    // approach from this far outside
  float depth_mm = 3.0f;            // below the surface, along the direction from the object's centre
  float depth_amplitude_mm = 1.0f;  // depth varies by this much, two cycles over the slide
  float length_mm = 50.0f;          // along a great circle about the object's bounds centre
  float speed_mm_per_s = 20.0f;
  float approach_s = 0.4f, retract_s = 0.3f;
  glm::vec2 screen_direction{1.0f, 0.0f};  // heading on screen: x right, y up
};

// A slide that follows the object's real surface: at each millisecond the tip is `depth_mm` below the
// surface point met by a ray from outside toward the object's centre, so it dips into sulci instead of
// ploughing through gyri (a slide at a fixed depth below a smooth sphere traps a god-object in the
// first groove). Starts at the surface seen through `pixel_px` and heads along `screen_direction`.
// `bvh` must hold the object. Throws when the view there misses the object.
ProbeScript surface_slide_script(const Scene& scene, const Bvh& bvh, int object, const OrbitCamera& camera,
                                 glm::vec2 pixel_px, glm::vec2 viewport_px, const SurfaceSlideParams& params);

}  // namespace palpate
