#include "palpate/haptics/press_slide_path.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <numbers>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/core/finite.hpp"

namespace palpate {
namespace {

void require(bool ok, const char* field, const std::string& why) {
  if (!ok) throw Error(std::string("press-slide path: ") + field + " " + why);
}

}  // namespace

PressSlidePath::PressSlidePath(const PressSlideParams& spec) : spec_(spec) {
  require(is_finite(spec.surface_point_mm), "surface_point_mm", "must be finite");
  require(is_finite(spec.normal) && glm::length(spec.normal) > 1e-6f, "normal",
          "must be a finite non-zero vector");
  normal_ = glm::normalize(spec.normal);
  require(is_finite(spec.slide_direction), "slide_direction", "must be finite");
  const glm::vec3 tangent = spec.slide_direction - normal_ * glm::dot(spec.slide_direction, normal_);
  require(glm::length(tangent) > 1e-3f * std::max(1.0f, glm::length(spec.slide_direction)), "slide_direction",
          "must not be along the normal");
  tangent_ = glm::normalize(tangent);
  for (auto [value, name] : {std::pair{spec.approach_speed_mm_per_s, "approach_speed_mm_per_s"},
                             std::pair{spec.slide_speed_mm_per_s, "slide_speed_mm_per_s"},
                             std::pair{spec.retract_speed_mm_per_s, "retract_speed_mm_per_s"}}) {
    require(std::isfinite(value) && value > 0.0f, name, "must be positive, got " + std::to_string(value));
  }
  require(std::isfinite(spec.slide_length_mm) && spec.slide_length_mm >= 0.0f, "slide_length_mm",
          "must be >= 0");
  require(std::isfinite(spec.curvature_radius_mm) && spec.curvature_radius_mm >= 0.0f, "curvature_radius_mm",
          "must be >= 0 (0 for a flat surface)");
  require(std::isfinite(spec.depth_amplitude_mm) && std::isfinite(spec.depth_cycles),
          "depth_amplitude_mm/depth_cycles", "must be finite");
  require(std::isfinite(spec.rest_s) && spec.rest_s >= 0.0f, "rest_s", "must be >= 0");
  require(std::isfinite(spec.press_depth_mm) && std::isfinite(spec.start_height_mm),
          "press_depth_mm/start_height_mm", "must be finite");
  const float deepest = std::abs(spec.press_depth_mm) + std::abs(spec.depth_amplitude_mm);
  require(spec.curvature_radius_mm == 0.0f || spec.curvature_radius_mm > deepest, "curvature_radius_mm",
          "must exceed the deepest press (" + std::to_string(deepest) + " mm)");
  require(spec.start_height_mm + spec.press_depth_mm > 0.0f &&
              spec.start_height_mm + depth_at(spec.slide_length_mm) > 0.0f,
          "start_height_mm", "must be above the press depth at both ends of the slide");
  approach_end_s_ = (double(spec.start_height_mm) + spec.press_depth_mm) / spec.approach_speed_mm_per_s;
  slide_end_s_ = approach_end_s_ + double(spec.slide_length_mm) / spec.slide_speed_mm_per_s;
  retract_end_s_ = slide_end_s_ + (double(spec.start_height_mm) + depth_at(spec.slide_length_mm)) /
                                      spec.retract_speed_mm_per_s;
  duration_s_ = retract_end_s_ + spec.rest_s;
}

float PressSlidePath::depth_at(float s_mm) const noexcept {
  if (spec_.slide_length_mm <= 0.0f) return spec_.press_depth_mm;
  const float phase = 2.0f * std::numbers::pi_v<float> * spec_.depth_cycles * s_mm / spec_.slide_length_mm;
  return spec_.press_depth_mm + spec_.depth_amplitude_mm * std::sin(phase);
}

glm::vec3 PressSlidePath::normal_at(float s_mm) const noexcept {
  if (spec_.curvature_radius_mm == 0.0f) return normal_;
  const float angle = s_mm / spec_.curvature_radius_mm;
  return std::cos(angle) * normal_ + std::sin(angle) * tangent_;
}

glm::vec3 PressSlidePath::surface_at(float s_mm) const noexcept {
  if (spec_.curvature_radius_mm == 0.0f) return spec_.surface_point_mm + tangent_ * s_mm;
  const glm::vec3 centre = spec_.surface_point_mm - normal_ * spec_.curvature_radius_mm;
  return centre + normal_at(s_mm) * spec_.curvature_radius_mm;
}

DeviceState PressSlidePath::sample(double time_s) const noexcept {
  DeviceState state;
  const double t = std::clamp(time_s, 0.0, duration_s_);
  const float length = spec_.slide_length_mm;
  if (t < approach_end_s_) {
    const float height = spec_.start_height_mm - spec_.approach_speed_mm_per_s * float(t);
    state.position_mm = spec_.surface_point_mm + normal_ * height;
    state.velocity_mm_per_s = -normal_ * spec_.approach_speed_mm_per_s;
  } else if (t < slide_end_s_) {
    const float speed = spec_.slide_speed_mm_per_s;
    const float s = speed * float(t - approach_end_s_);
    const float depth = depth_at(s);
    const float depth_slope =
        length > 0.0f
            ? spec_.depth_amplitude_mm * 2.0f * std::numbers::pi_v<float> * spec_.depth_cycles / length *
                  std::cos(2.0f * std::numbers::pi_v<float> * spec_.depth_cycles * s / length)
            : 0.0f;
    const glm::vec3 n = normal_at(s);
    state.position_mm = surface_at(s) - n * depth;
    // d/ds of (surface - n depth): the tangent scaled by (R - depth) / R on a sphere, minus n depth'.
    glm::vec3 along = tangent_;
    float tangential_scale = 1.0f;
    if (spec_.curvature_radius_mm > 0.0f) {
      const float angle = s / spec_.curvature_radius_mm;
      along = -std::sin(angle) * normal_ + std::cos(angle) * tangent_;
      tangential_scale = (spec_.curvature_radius_mm - depth) / spec_.curvature_radius_mm;
    }
    state.velocity_mm_per_s = speed * (along * tangential_scale - n * depth_slope);
  } else if (t < retract_end_s_) {
    const float height = -depth_at(length) + spec_.retract_speed_mm_per_s * float(t - slide_end_s_);
    const glm::vec3 n = normal_at(length);
    state.position_mm = surface_at(length) + n * height;
    state.velocity_mm_per_s = n * spec_.retract_speed_mm_per_s;
  } else {
    state.position_mm = surface_at(length) + normal_at(length) * spec_.start_height_mm;
  }
  return state;
}

PressSlideParams aim_press_slide(const SceneObject& object, std::size_t vertex, glm::vec3 slide_direction,
                                 PressSlideParams spec, float smoothing_radius_mm) {
  const Mesh& mesh = object.mesh;
  if (vertex >= mesh.positions_mm.size()) {
    throw Error("aim_press_slide: vertex " + std::to_string(vertex) + " of '" + object.name +
                "' is out of range (" + std::to_string(mesh.positions_mm.size()) + " vertices)");
  }
  Mesh with_normals;
  const Mesh* normals_from = &mesh;
  if (mesh.normals.size() != mesh.positions_mm.size()) {
    with_normals = mesh;
    compute_vertex_normals(with_normals);
    normals_from = &with_normals;
  }
  const glm::vec3 local = mesh.positions_mm[vertex];
  glm::vec3 normal_sum(0.0f);
  for (std::size_t v = 0; v < mesh.positions_mm.size(); ++v) {
    if (glm::length(mesh.positions_mm[v] - local) <= smoothing_radius_mm)
      normal_sum += normals_from->normals[v];
  }
  if (glm::length(normal_sum) < 1e-6f) normal_sum = normals_from->normals[vertex];
  const glm::vec3 centre = glm::vec3(object.transform * glm::vec4(bounds(mesh).center_mm(), 1.0f));
  spec.surface_point_mm = glm::vec3(object.transform * glm::vec4(local, 1.0f));
  spec.normal = glm::normalize(glm::mat3(object.transform) * normal_sum);
  spec.slide_direction = slide_direction;
  // The sphere about the centre fits where the surface faces away from it (a head, a brain); elsewhere
  // (a sheet, a dent, a thin part) slide flat.
  const glm::vec3 from_centre = spec.surface_point_mm - centre;
  const float radius = glm::length(from_centre);
  const float deepest = std::abs(spec.press_depth_mm) + std::abs(spec.depth_amplitude_mm);
  const bool faces_away = radius > 0.0f && glm::dot(spec.normal, from_centre / radius) > 0.7f;
  spec.curvature_radius_mm = faces_away && radius > 2.0f * deepest ? radius : 0.0f;
  return spec;
}

}  // namespace palpate
