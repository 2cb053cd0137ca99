#pragma once
// The paper's system (its Fig. 7) in one process, driven by a script: the haptic loop runs on its own
// thread at its rate on the undeformed scene, moving a ScriptedDevice along a ProbeScript, and the
// calling thread draws frame after frame, each deformed by the latest tick result, read without
// blocking the haptic thread. It measures what the paper's Table I reports: graphics frame rate and
// haptic rate together, and how old the contact each frame drew was. For demos, benchmarks and tests of
// the whole chain; an application with its own frame loop does the same with HapticLoop::latest().
//
// Needs the context of `framebuffer` current; allocates; throws palpate::Error from setup.
#include <cstddef>
#include <functional>
#include <glm/mat4x4.hpp>
#include <string>
#include <vector>

#include "palpate/core/orbit_camera.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/renderer.hpp"
#include "palpate/gl/stereo_compositor.hpp"
#include "palpate/gl/window.hpp"
#include "palpate/haptics/haptic_pipeline.hpp"
#include "palpate/haptics/loop_statistics.hpp"
#include "palpate/haptics/probe_script.hpp"

namespace palpate::gl {

struct CapturedFrame {
  int index = 0;        // capture number within the run
  double time_s = 0.0;  // haptic run time at the frame
  TickResult tick;      // what the frame was drawn with
  glm::mat4 view{1.0f}, projection{1.0f};
  const Framebuffer* framebuffer = nullptr;  // holds the frame (read it before returning)
};

struct ProbeRunParams {
  DrawParams draw;  // how each frame is drawn (deformation, probe size, lights)
  double haptic_rate_hz = 1000.0;
  double capture_fps = 0.0;   // frames handed to on_capture per second of run time; 0: none
  int captures_so_far = 0;    // numbering of the captures (CapturedFrame::index) starts here
  int max_captures = -1;      // stop after the capture numbered this -1; -1: no limit
  double max_seconds = -1.0;  // stop after this much run time; -1: the script's length
  Window* window = nullptr;   // also shown there when given
  // Stereo: each frame drawn once per eye and combined (mono with no mirror: drawn straight into the
  // framebuffer). The frames are offscreen, so quad_buffer is refused (palpate::Error).
  StereoMode stereo = StereoMode::mono;
  Mirror mirror = Mirror::none;
  StereoCamera stereo_camera;
  std::function<void(const CapturedFrame&)> on_capture;
  std::function<void(const std::string&)> on_log;  // the haptic loop's notices (see HapticLoopParams)
};

struct ProbeRunResult {
  std::size_t vertices = 0, faces = 0;  // of the visible objects
  int frames = 0;
  double seconds = 0.0;
  double graphics_fps = 0.0;   // frames over the time spent drawing them (capture excluded)
  double haptics_hz = 0.0;     // ticks over the run's length
  Percentiles contact_age_ms;  // how old the tick result each frame drew was
  double max_force_n = 0.0;    // the largest force among the ticks the frames drew
  LoopStatistics haptics;
  std::vector<double> frame_ms;       // each frame's drawing time
  std::vector<double> frame_times_s;  // run time at each frame
  int captures = 0;
};

// Uploads `scene` to `renderer`, runs the script through a HapticLoop on a BVH of the scene, and draws
// into `framebuffer` with `camera` until the script ends (or max_seconds, max_captures, or the window
// closes).
ProbeRunResult run_probe_script(const Scene& scene, const OrbitCamera& camera, const ProbeScript& script,
                                Renderer& renderer, const Framebuffer& framebuffer,
                                const ProbeRunParams& params);

}  // namespace palpate::gl
