#include "palpate/haptics/probe_script.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/core/pick.hpp"

namespace palpate {
namespace {

constexpr double sample_s = 1e-3;

// Appends a straight move from the last sample to `to` at `speed_mm_per_s`, sampled every millisecond.
void move_to(std::vector<PathSample>& samples, glm::vec3 to, float speed_mm_per_s) {
  const PathSample from = samples.back();
  const double duration = std::max(sample_s, double(glm::distance(from.position_mm, to)) / speed_mm_per_s);
  const int steps = std::max(1, int(std::ceil(duration / sample_s)));
  for (int i = 1; i <= steps; ++i) {
    const float f = float(i) / float(steps);
    samples.push_back({from.time_s + duration * f, glm::mix(from.position_mm, to, f)});
  }
}

std::vector<std::uint8_t> only(const Scene& scene, const Bvh& bvh, int object) {
  if (object < 0 || std::size_t(object) >= scene.objects.size() || !bvh.contains(object)) {
    throw Error("probe script: object " + std::to_string(object) + " is not in the scene's BVH");
  }
  std::vector<std::uint8_t> mask(scene.objects.size(), 0);
  mask[std::size_t(object)] = 1;
  return mask;
}

glm::vec3 camera_axis(const OrbitCamera& camera, int row) {
  const glm::mat4 view = camera.view();
  return {view[0][row], view[1][row], view[2][row]};
}

std::string missed(const Scene& scene, int object, glm::vec2 pixel_px) {
  return "probe script: the view ray through pixel (" + std::to_string(int(pixel_px.x)) + ", " +
         std::to_string(int(pixel_px.y)) + ") misses object '" + scene.objects[std::size_t(object)].name +
         "'";
}

}  // namespace

ProbeScript press_script(std::span<const PressSlideParams> presses, float clearance_mm) {
  if (presses.empty()) throw Error("probe script: no presses");
  std::vector<PathSample> samples;
  std::vector<ProbeScript::Stroke> strokes;
  glm::vec3 previous_normal{0.0f};
  for (const PressSlideParams& spec : presses) {
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
    const int steps = int(std::ceil(path.duration_s() / sample_s));
    for (int i = 1; i <= steps; ++i) {
      const double t = std::min(path.duration_s(), i * sample_s);
      samples.push_back({offset + t, path.sample(t).position_mm});
    }
    previous_normal = path.normal_at(spec.slide_length_mm);
  }
  return ProbeScript{SampledPath(std::move(samples)), std::move(strokes)};
}

std::vector<PressSlideParams> aim_at_view(const Scene& scene, const Bvh& bvh, int object,
                                          const OrbitCamera& camera, std::span<const glm::vec2> sites_px,
                                          glm::vec2 viewport_px, const PressSlideParams& params) {
  const std::vector<std::uint8_t> mask = only(scene, bvh, object);
  const SceneObject& target = scene.objects[std::size_t(object)];
  const glm::mat4 to_object = glm::inverse(target.transform);
  std::vector<PressSlideParams> presses;
  for (const glm::vec2 site : sites_px) {
    const BvhHit hit = pick(bvh, camera, site, viewport_px, mask);
    if (!hit.hit()) throw Error(missed(scene, object, site));
    // The hit triangle's vertex nearest the hit, in the object's frame.
    const glm::vec3 local = glm::vec3(to_object * glm::vec4(hit.point_mm, 1.0f));
    const std::uint32_t* corners = &target.mesh.indices[std::size_t(hit.triangle) * 3];
    const std::uint32_t nearest =
        *std::min_element(corners, corners + 3, [&](std::uint32_t a, std::uint32_t b) {
          return glm::distance(target.mesh.positions_mm[a], local) <
                 glm::distance(target.mesh.positions_mm[b], local);
        });
    presses.push_back(aim_press_slide(target, nearest, camera_axis(camera, 0), params));
  }
  return presses;
}

ProbeScript surface_slide_script(const Scene& scene, const Bvh& bvh, int object, const OrbitCamera& camera,
                                 glm::vec2 pixel_px, glm::vec2 viewport_px,
                                 const SurfaceSlideParams& params) {
  const std::vector<std::uint8_t> mask = only(scene, bvh, object);
  const BvhHit start = pick(bvh, camera, pixel_px, viewport_px, mask);
  if (!start.hit()) throw Error(missed(scene, object, pixel_px));
  const glm::vec3 centre = world_bounds(scene.objects[std::size_t(object)]).center_mm();
  const glm::vec3 radial0 = glm::normalize(start.point_mm - centre);
  const glm::vec3 heading =
      camera_axis(camera, 0) * params.screen_direction.x + camera_axis(camera, 1) * params.screen_direction.y;
  const glm::vec3 axis = glm::normalize(glm::cross(radial0, heading));
  const float radius = glm::distance(start.point_mm, centre);
  const float reach = 2.0f * radius;

  // The tip below the surface met from outside along the radial direction, `s_mm` along the arc.
  glm::vec3 last_tip = start.point_mm - radial0 * params.depth_mm;
  const auto tip_at = [&](float s_mm, float depth_mm) {
    const glm::vec3 radial =
        glm::vec3(glm::rotate(glm::mat4(1.0f), s_mm / radius, axis) * glm::vec4(radial0, 0.0f));
    const BvhHit hit = bvh.first_hit(glm::dvec3(centre + radial * (radius + reach)), glm::dvec3(centre),
                                     Faces::front, 0.0, mask);
    if (hit.hit()) last_tip = hit.point_mm - radial * depth_mm;
    return last_tip;
  };
  const glm::vec3 outside = start.point_mm + radial0 * params.start_height_mm;
  std::vector<PathSample> samples{{0.0, outside}};
  const auto add = [&](glm::vec3 p) { samples.push_back({samples.back().time_s + sample_s, p}); };
  const int approach = std::max(1, int(params.approach_s / sample_s));
  const glm::vec3 first = tip_at(0.0f, params.depth_mm);
  for (int i = 1; i <= approach; ++i) add(glm::mix(outside, first, float(i) / float(approach)));
  const int slide = std::max(1, int(params.length_mm / params.speed_mm_per_s / sample_s));
  for (int i = 1; i <= slide; ++i) {
    const float s = params.length_mm * float(i) / float(slide);
    add(tip_at(s, params.depth_mm + params.depth_amplitude_mm *
                                        std::sin(4.0f * std::numbers::pi_v<float> * s / params.length_mm)));
  }
  const glm::vec3 last = samples.back().position_mm;
  const glm::vec3 away = last + glm::normalize(last - centre) * (params.start_height_mm + params.depth_mm);
  const int retract = std::max(1, int(params.retract_s / sample_s));
  for (int i = 1; i <= retract; ++i) add(glm::mix(last, away, float(i) / float(retract)));
  const double end = samples.back().time_s;
  return ProbeScript{SampledPath(std::move(samples)), {{0.0, end, true}}};
}

}  // namespace palpate
