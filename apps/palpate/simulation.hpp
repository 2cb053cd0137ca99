#pragma once
// The paper's system (its Fig. 7) in one process: the haptic loop at 1 kHz on its own thread, on the
// undeformed geometry, and the graphics loop on this thread, which reads the latest contact each frame
// without blocking the haptic thread and draws the scene deformed. Used by `demo` and `bench table1`.
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "palpate/core/orbit_camera.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/renderer.hpp"
#include "palpate/gl/window.hpp"
#include "palpate/haptics/loop_statistics.hpp"
#include "palpate/haptics/press_slide_path.hpp"
#include "palpate/haptics/sampled_path.hpp"

namespace palpate::cli {

// What the scripted probe does: a device path sampled every millisecond, and the strokes on it.
struct ProbeScript {
  struct Stroke {
    double start_s = 0.0, end_s = 0.0;  // from the start of the approach to the end of the pull-out
    bool slide = false;                 // a long slide (else a press)
  };
  SampledPath path{{PathSample{}}};
  std::vector<Stroke> strokes;
};

// One stretch of a run: a scene state (which objects are visible and touchable), a camera and what
// the probe does.
struct Phase {
  std::string model;  // the row name in the paper's Table I: "Brain", "Skin", "Skin + Brain"
  Scene scene;
  OrbitCamera camera;
  ProbeScript script;
  float probe_radius_mm = 1.5f;  // the sphere drawn at the tip
};

// Presses one after the other, with transits between them that leave along the normal to
// `clearance_mm` so the tip never cuts through the object in free flight.
ProbeScript press_script(const std::vector<PressSlide>& presses, float clearance_mm = 60.0f);

struct SurfaceSlide {
  float start_height_mm = 12.0f;    // approach from this far outside
  float depth_mm = 3.0f;            // below the surface, along the direction from the object's centre
  float depth_amplitude_mm = 1.0f;  // depth varies by this much, two cycles over the slide
  float length_mm = 50.0f;          // along a great circle about the object's bounds centre
  float speed_mm_per_s = 20.0f;
  float approach_s = 0.4f, retract_s = 0.3f;
  glm::vec2 screen_direction{1.0f, 0.0f};  // heading on screen: x right, y up
};

// A slide that follows the object's real surface: at each millisecond the tip is `depth` below the
// surface point found by a ray toward the object's centre, so it dips into sulci instead of ploughing
// through gyri (a slide at a fixed depth below a smooth sphere traps a god-object in the first
// groove). Starts at the surface seen through the viewport position `where` and heads along
// `screen_direction`. Throws palpate::Error when the view misses the object.
ProbeScript surface_slide_script(const Scene& scene, int object_index, const OrbitCamera& camera,
                                 glm::vec2 where, const SurfaceSlide& spec);

// Presses at the surface points of `object_index` seen from the camera through the viewport
// positions `sites` (x, y in [0, 1] from the top left), each sliding toward the camera's right.
// Throws palpate::Error when a ray misses the object.
std::vector<PressSlide> aim_at_view(const Scene& scene, int object_index, const OrbitCamera& camera,
                                    std::span<const glm::vec2> sites, const PressSlide& spec);

struct CapturedFrame {
  int index = 0;        // capture number within the run
  double time_s = 0.0;  // haptic run time at the frame
  Contact contact;      // what the frame was drawn with
  glm::mat4 view{1.0f}, projection{1.0f};
  const gl::Framebuffer* framebuffer = nullptr;  // holds the frame (read it before returning)
};

struct RunOptions {
  gl::Deformation deformation = gl::Deformation::gpu;
  double haptic_rate_hz = 1000.0;
  double capture_fps = 0.0;      // frames handed to on_capture per second of run time; 0: none
  int max_captures = -1;         // stop the run after this many captures; -1: no limit
  double max_seconds = -1.0;     // stop the phase after this much run time; -1: the script's length
  gl::Window* window = nullptr;  // also shown there when given
  std::function<void(const CapturedFrame&)> on_capture;
};

struct PhaseResult {
  std::string model;
  std::size_t vertices = 0, faces = 0;  // of the visible objects
  int frames = 0;
  double seconds = 0.0;
  double graphics_fps = 0.0;   // frames over the time spent drawing them (capture excluded)
  double haptics_hz = 0.0;     // ticks over the run's length
  Percentiles contact_age_ms;  // how old the contact each frame drew was
  LoopStatistics haptics;
  std::vector<double> frame_ms;       // each frame's drawing time
  std::vector<double> frame_times_s;  // run time at each frame
  int captures = 0;
};

// Runs one phase on `framebuffer` (bound by the caller's context). Returns when the script ends, when
// max_seconds or max_captures is reached, or when the window is closed.
PhaseResult run_phase(const Phase& phase, gl::Renderer& renderer, const gl::Framebuffer& framebuffer,
                      const RunOptions& options, int captures_so_far = 0);

}  // namespace palpate::cli
