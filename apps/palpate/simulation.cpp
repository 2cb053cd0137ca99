#include "simulation.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>

#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/haptics/haptic_loop.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate::cli {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Appends a straight move from the last sample to `to` at `speed_mm_per_s`, sampled every millisecond.
void move_to(std::vector<PathSample>& samples, glm::vec3 to, float speed_mm_per_s) {
  const PathSample from = samples.back();
  const double duration = std::max(1e-3, double(glm::distance(from.position_mm, to)) / speed_mm_per_s);
  const int steps = std::max(1, int(std::ceil(duration / 1e-3)));
  for (int i = 1; i <= steps; ++i) {
    const float f = float(i) / float(steps);
    samples.push_back({from.time_s + duration * f, glm::mix(from.position_mm, to, f)});
  }
}

}  // namespace

ProbeScript press_script(const std::vector<PressSlide>& presses, float clearance_mm) {
  if (presses.empty()) throw Error("probe script: no presses");
  std::vector<PathSample> samples;
  std::vector<ProbeScript::Stroke> strokes;
  glm::vec3 previous_normal{0.0f};
  for (const PressSlide& spec : presses) {
    const PressSlidePath path(spec);
    const glm::vec3 normal = glm::normalize(spec.normal);
    const glm::vec3 start = path.sample(0.0).position_mm;
    if (!samples.empty()) {
      // Leave the last site along its normal, cross over, come down on the next one's normal.
      const float rise = std::max(0.0f, clearance_mm - spec.start_height_mm);
      move_to(samples, samples.back().position_mm + previous_normal * rise, 200.0f);
      move_to(samples, start + normal * rise, 200.0f);
      move_to(samples, start, 200.0f);
    } else {
      samples.push_back({0.0, start});
    }
    const double offset = samples.back().time_s;
    strokes.push_back({offset, offset + path.duration_s(), false});
    const int steps = int(std::ceil(path.duration_s() / 1e-3));
    for (int i = 1; i <= steps; ++i) {
      const double t = std::min(path.duration_s(), i * 1e-3);
      samples.push_back({offset + t, path.sample(t).position_mm});
    }
    previous_normal = path.normal_at(spec.slide_length_mm);
  }
  return ProbeScript{SampledPath(std::move(samples)), std::move(strokes)};
}

namespace {

// The first front-facing hit of a segment on one object of the scene, or no hit.
class ObjectCaster {
 public:
  ObjectCaster(const Scene& scene, int object_index) : bvh_(Bvh::build(only(scene, object_index))) {}
  BvhHit cast(glm::vec3 from, glm::vec3 to) const { return bvh_.first_hit(glm::dvec3(from), glm::dvec3(to)); }

 private:
  static Scene only(const Scene& scene, int object_index) {
    Scene out = scene;
    for (std::size_t i = 0; i < out.objects.size(); ++i)
      out.objects[i].material.touchable = int(i) == object_index;
    return out;
  }
  Bvh bvh_;
};

OrbitCamera::Ray view_ray(const OrbitCamera& camera, glm::vec2 where) {
  const glm::vec2 viewport{1000.0f, 1000.0f * 0.8f};
  return camera.ray_through(where * viewport, viewport);
}

glm::vec3 camera_right(const OrbitCamera& camera) {
  const glm::mat4 view = camera.view();
  return {view[0][0], view[1][0], view[2][0]};
}

glm::vec3 camera_up(const OrbitCamera& camera) {
  const glm::mat4 view = camera.view();
  return {view[0][1], view[1][1], view[2][1]};
}

std::string missed(const Scene& scene, int object_index, glm::vec2 where) {
  return "probe script: the view ray through (" + std::to_string(where.x) + ", " + std::to_string(where.y) +
         ") misses object '" + scene.objects[std::size_t(object_index)].name + "'";
}

}  // namespace

ProbeScript surface_slide_script(const Scene& scene, int object_index, const OrbitCamera& camera,
                                 glm::vec2 where, const SurfaceSlide& spec) {
  const ObjectCaster caster(scene, object_index);
  const OrbitCamera::Ray ray = view_ray(camera, where);
  const BvhHit start = caster.cast(ray.origin, ray.origin + ray.direction * camera.distance_mm * 4.0f);
  if (!start.hit()) throw Error(missed(scene, object_index, where));
  const glm::vec3 centre = world_bounds(scene.objects[std::size_t(object_index)]).center();
  const glm::vec3 radial0 = glm::normalize(start.point - centre);
  const glm::vec3 heading =
      camera_right(camera) * spec.screen_direction.x + camera_up(camera) * spec.screen_direction.y;
  const glm::vec3 axis = glm::normalize(glm::cross(radial0, heading));
  const float radius = glm::distance(start.point, centre);
  const float reach = 2.0f * radius;

  // The tip below the surface met from outside along the radial direction, `s` mm along the arc.
  glm::vec3 last_tip = start.point - radial0 * spec.depth_mm;
  const auto tip_at = [&](float s_mm, float depth_mm) {
    const glm::vec3 radial =
        glm::vec3(glm::rotate(glm::mat4(1.0f), s_mm / radius, axis) * glm::vec4(radial0, 0.0f));
    const BvhHit hit = caster.cast(centre + radial * (radius + reach), centre);
    if (hit.hit()) last_tip = hit.point - radial * depth_mm;
    return last_tip;
  };
  const glm::vec3 outside = start.point + radial0 * spec.start_height_mm;
  std::vector<PathSample> samples{{0.0, outside}};
  const auto add = [&](double dt, glm::vec3 p) { samples.push_back({samples.back().time_s + dt, p}); };
  const int approach = std::max(1, int(spec.approach_s * 1000.0f));
  const glm::vec3 first = tip_at(0.0f, spec.depth_mm);
  for (int i = 1; i <= approach; ++i) add(1e-3, glm::mix(outside, first, float(i) / float(approach)));
  const int slide = std::max(1, int(spec.length_mm / spec.speed_mm_per_s * 1000.0f));
  for (int i = 1; i <= slide; ++i) {
    const float s = spec.length_mm * float(i) / float(slide);
    add(1e-3, tip_at(s, spec.depth_mm + spec.depth_amplitude_mm *
                                            std::sin(4.0f * std::numbers::pi_v<float> * s / spec.length_mm)));
  }
  const glm::vec3 last = samples.back().position_mm;
  const glm::vec3 away = last + glm::normalize(last - centre) * (spec.start_height_mm + spec.depth_mm);
  const int retract = std::max(1, int(spec.retract_s * 1000.0f));
  for (int i = 1; i <= retract; ++i) add(1e-3, glm::mix(last, away, float(i) / float(retract)));
  const double end = samples.back().time_s;
  return ProbeScript{SampledPath(std::move(samples)), {{0.0, end, true}}};
}

std::vector<PressSlide> aim_at_view(const Scene& scene, int object_index, const OrbitCamera& camera,
                                    std::span<const glm::vec2> sites, const PressSlide& spec) {
  const ObjectCaster caster(scene, object_index);
  const SceneObject& object = scene.objects[std::size_t(object_index)];
  const glm::mat4 to_object = glm::inverse(object.transform);
  std::vector<PressSlide> presses;
  for (const glm::vec2 where : sites) {
    const OrbitCamera::Ray ray = view_ray(camera, where);
    const BvhHit hit = caster.cast(ray.origin, ray.origin + ray.direction * camera.distance_mm * 4.0f);
    if (!hit.hit()) throw Error(missed(scene, object_index, where));
    // The hit triangle's vertex nearest the hit, in the object's frame.
    const glm::vec3 local = glm::vec3(to_object * glm::vec4(hit.point, 1.0f));
    std::size_t nearest = object.mesh.indices[std::size_t(hit.triangle) * 3];
    for (int k = 1; k < 3; ++k) {
      const std::size_t v = object.mesh.indices[std::size_t(hit.triangle) * 3 + std::size_t(k)];
      if (glm::distance(object.mesh.positions[v], local) <
          glm::distance(object.mesh.positions[nearest], local))
        nearest = v;
    }
    presses.push_back(aim_press_slide(object, nearest, camera_right(camera), spec));
  }
  return presses;
}

PhaseResult run_phase(const Phase& phase, gl::Renderer& renderer, const gl::Framebuffer& framebuffer,
                      const RunOptions& options, int captures_so_far) {
  PhaseResult result;
  result.model = phase.model;
  for (const SceneObject& object : phase.scene.objects) {
    if (!object.material.visible) continue;
    result.vertices += object.mesh.vertex_count();
    result.faces += object.mesh.triangle_count();
  }
  const Bvh bvh = Bvh::build(phase.scene);
  ScriptedDevice device(phase.script.path);
  HapticLoopParams params;
  params.rate_hz = options.haptic_rate_hz;
  HapticLoop loop(device, phase.scene, bvh, params);
  renderer.upload(phase.scene);

  const float aspect = float(framebuffer.width()) / float(framebuffer.height());
  const glm::mat4 view = phase.camera.view(), projection = phase.camera.projection(aspect);
  const double end_s = options.max_seconds > 0.0 ? options.max_seconds : phase.script.path.end_s() + 0.1;
  std::vector<double> ages_ms;
  ages_ms.reserve(4096);
  gl::DrawOptions draw;
  draw.deformation = options.deformation;
  draw.probe_radius_mm = phase.probe_radius_mm;
  double next_capture_s = 0.0;
  double drawing_s = 0.0;

  loop.start();
  const Clock::time_point started = Clock::now();
  for (;;) {
    const double now_s = loop.run_time_s();
    if (now_s > end_s) break;
    if (options.max_captures >= 0 && captures_so_far + result.captures >= options.max_captures) break;
    if (options.window && options.window->should_close()) break;

    const Contact contact = loop.latest_contact();
    if (contact.tick > 0) ages_ms.push_back((loop.run_time_s() - contact.time_s) * 1e3);
    const Clock::time_point frame_start = Clock::now();
    framebuffer.bind();
    glClearColor(0.08f, 0.09f, 0.11f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    renderer.draw(view, projection, std::span<const Contact>(&contact, 1), draw);
    glFinish();  // llvmpipe has no trustworthy timer queries: a frame is done when glFinish returns
    const double frame_s = seconds_since(frame_start);
    drawing_s += frame_s;
    ++result.frames;
    result.frame_ms.push_back(frame_s * 1e3);
    result.frame_times_s.push_back(now_s);

    if (options.capture_fps > 0.0 && options.on_capture && now_s >= next_capture_s) {
      options.on_capture(
          CapturedFrame{captures_so_far + result.captures, now_s, contact, view, projection, &framebuffer});
      ++result.captures;
      next_capture_s += 1.0 / options.capture_fps;
      if (next_capture_s < now_s) next_capture_s = now_s;  // drawing slower than the capture rate: no burst
    }
    if (options.window) {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer.id());
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      glBlitFramebuffer(0, 0, framebuffer.width(), framebuffer.height(), 0, 0,
                        options.window->framebuffer_width(), options.window->framebuffer_height(),
                        GL_COLOR_BUFFER_BIT, GL_LINEAR);
      options.window->swap_buffers();
      gl::Window::poll_events();
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

}  // namespace palpate::cli
