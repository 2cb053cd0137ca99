#include "palpate/gl/probe_run.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <glm/geometric.hpp>
#include <optional>

#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/haptics/haptic_loop.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate::gl {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

ProbeRunResult run_probe_script(const Scene& scene, const OrbitCamera& camera, const ProbeScript& script,
                                Renderer& renderer, const Framebuffer& framebuffer,
                                const ProbeRunParams& params) {
  if (params.stereo == StereoMode::quad_buffer) {
    throw Error(
        "run_probe_script draws offscreen frames: quad-buffered stereo needs a window's back buffers");
  }
  ProbeRunResult result;
  for (const SceneObject& object : scene.objects) {
    if (!object.material.visible) continue;
    result.vertices += object.mesh.vertex_count();
    result.faces += object.mesh.triangle_count();
  }
  const Bvh bvh = Bvh::build(scene);
  ScriptedDevice device(script.path);
  HapticLoopParams loop_params;
  loop_params.rate_hz = params.haptic_rate_hz;
  loop_params.on_log = params.on_log;
  HapticLoop loop(device, scene, bvh, loop_params);
  renderer.upload(scene);

  std::optional<StereoCompositor> compositor;
  if (params.stereo != StereoMode::mono || params.mirror != Mirror::none) compositor.emplace();
  const float aspect = float(framebuffer.width()) / float(framebuffer.height());
  const glm::mat4 view = camera.view(), projection = camera.projection(aspect);
  const double end_s = params.max_seconds > 0.0 ? params.max_seconds : script.path.end_s() + 0.1;
  std::vector<double> ages_ms;
  ages_ms.reserve(4096);
  double next_capture_s = 0.0;
  double drawing_s = 0.0;

  loop.start();
  const Clock::time_point started = Clock::now();
  for (;;) {
    const double now_s = loop.run_time_s();
    if (now_s > end_s) break;
    if (params.max_captures >= 0 && params.captures_so_far + result.captures >= params.max_captures) break;
    if (params.window && params.window->should_close()) break;

    const TickResult tick = loop.latest();
    if (tick.contact.tick > 0) ages_ms.push_back((loop.run_time_s() - tick.contact.time_s) * 1e3);
    result.max_force_n = std::max(result.max_force_n, double(glm::length(tick.force_n)));
    const Clock::time_point frame_start = Clock::now();
    framebuffer.bind();
    const auto draw = [&](const glm::mat4& eye_view, const glm::mat4& eye_projection) {
      glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      renderer.draw(eye_view, eye_projection, std::span<const Contact>(&tick.contact, 1), params.draw);
    };
    if (compositor) {
      compositor->render(params.stereo, params.mirror, framebuffer.width(), framebuffer.height(),
                         [&](const EyeTarget& target) {
                           const EyeView eye =
                               params.stereo_camera.eye(target.eye, mono_camera(camera, target.aspect));
                           draw(eye.view, eye.projection);
                         });
    } else {
      draw(view, projection);
    }
    glFinish();  // llvmpipe has no trustworthy timer queries: a frame is done when glFinish returns
    const double frame_s = seconds_since(frame_start);
    drawing_s += frame_s;
    ++result.frames;
    result.frame_ms.push_back(frame_s * 1e3);
    result.frame_times_s.push_back(now_s);

    if (params.capture_fps > 0.0 && params.on_capture && now_s >= next_capture_s) {
      params.on_capture(CapturedFrame{params.captures_so_far + result.captures, now_s, tick, view, projection,
                                      &framebuffer});
      ++result.captures;
      next_capture_s += 1.0 / params.capture_fps;
      if (next_capture_s < now_s) next_capture_s = now_s;  // drawing slower than the capture rate: no burst
    }
    if (params.window) {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer.id());
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      glBlitFramebuffer(0, 0, framebuffer.width(), framebuffer.height(), 0, 0,
                        params.window->framebuffer_width(), params.window->framebuffer_height(),
                        GL_COLOR_BUFFER_BIT, GL_LINEAR);
      params.window->swap_buffers();
      Window::poll_events();
    }
  }
  result.seconds = seconds_since(started);
  const double run_s = loop.run_time_s();
  loop.stop();
  result.haptics = loop.statistics();
  result.graphics_fps = drawing_s > 0.0 ? result.frames / drawing_s : 0.0;
  result.haptics_hz = run_s > 0.0 ? double(result.haptics.ticks) / run_s : 0.0;
  result.contact_age_ms = percentiles(ages_ms);
  return result;
}

}  // namespace palpate::gl
