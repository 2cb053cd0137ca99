#include "haptic_scenarios.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>

#include <glm/geometric.hpp>

#include "palpate/core/error.hpp"
#include "palpate/haptics/haptic_pipeline.hpp"
#include "palpate/haptics/press_slide_path.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate::cli {
namespace {

// A cycle is "stuck" when, in contact, the proxy trails the tip by more than this beyond the
// tip's depth: a frictionless proxy sits on the surface near the tip, so |SCP - HIP| stays close to
// the depth (it can only be less); more means it is caught behind while the tip moves on.
constexpr double stuck_lag_mm = 1.0;
constexpr double pop_through_depth_mm = 0.5;
constexpr double inward_force_depth_mm = 0.2;

glm::vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> normal;
  glm::vec3 d;
  do d = {normal(rng), normal(rng), normal(rng)};
  while (glm::length(d) < 1e-3f);
  return glm::normalize(d);
}

glm::vec3 random_tangent(std::mt19937& rng, glm::vec3 n) {
  glm::vec3 t;
  do t = glm::cross(n, random_direction(rng));
  while (glm::length(t) < 1e-3f);
  return glm::normalize(t);
}

PressSlide press_slide(glm::vec3 point, glm::vec3 normal, glm::vec3 tangent, float curvature_radius,
                       const CycleShape& shape) {
  PressSlide spec;
  spec.surface_point_mm = point;
  spec.normal = normal;
  spec.slide_direction = tangent;
  spec.curvature_radius_mm = curvature_radius;
  spec.press_depth_mm = shape.press_depth_mm;
  spec.depth_amplitude_mm = shape.depth_amplitude_mm;
  const PressSlidePath timing(spec);
  spec.rest_s = float(std::max(0.0, shape.ticks_per_cycle * 1e-3 - timing.retract_end_s()));
  return spec;
}

}  // namespace

double BumpySphereReference::radius_at(glm::dvec3 u) const noexcept {
  return radius_mm_ + bump_mm_ * std::sin(15.0 * u.x) * std::sin(15.0 * u.y) * std::sin(15.0 * u.z + 0.7);
}

double BumpySphereReference::implicit(glm::dvec3 p) const noexcept {
  const double r = glm::length(p);
  return radius_at(p / r) - r;
}

glm::dvec3 BumpySphereReference::gradient(glm::dvec3 p) const noexcept {
  const double h = 1e-4;
  glm::dvec3 g;
  for (int axis = 0; axis < 3; ++axis) {
    glm::dvec3 step(0.0);
    step[axis] = h;
    g[axis] = (implicit(p + step) - implicit(p - step)) / (2.0 * h);
  }
  return g;
}

double BumpySphereReference::depth_mm(glm::vec3 p) const noexcept {
  return implicit(glm::dvec3(p)) / glm::length(gradient(glm::dvec3(p)));
}

glm::vec3 BumpySphereReference::outward_normal(glm::vec3 p) const noexcept {
  return glm::vec3(-glm::normalize(gradient(glm::dvec3(p))));
}

void BumpySphereReference::verify(const Mesh& mesh) const {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 v(mesh.positions[i]);
    const double off = std::abs(glm::length(v) - radius_at(glm::normalize(v)));
    if (!(off <= 1e-3)) {
      throw Error("bench haptics: vertex " + std::to_string(i) + " of the bumpy sphere is " + std::to_string(off) +
                  " mm off the reference surface: make_bumpy_sphere changed, update BumpySphereReference");
    }
  }
}

ScenarioResult run_cycles(const Scene& scene, const Bvh& bvh, const std::vector<SampledPath>& cycles, float max_force_n,
                          const BumpySphereReference* reference) {
  ScenarioResult result;
  std::size_t total = 0;
  for (const SampledPath& path : cycles) total += path.samples().size();
  result.free_tick_us.reserve(total);
  result.contact_tick_us.reserve(total);
  if (reference) result.checks = PathChecks{};
  DeviceLimits limits;
  limits.max_force_n = max_force_n;
  for (const SampledPath& path : cycles) {
    ScriptedDevice device(path, false, limits);
    HapticPipeline pipeline(device, scene, bvh);
    pipeline.reset_proxy(path.samples().front().position_mm);
    bool stuck = false;
    for (std::size_t k = 0; k < path.samples().size(); ++k) {
      const double time_s = path.samples()[k].time_s;
      const auto start = std::chrono::steady_clock::now();
      const TickResult tick = pipeline.tick(k, time_s);
      const auto end = std::chrono::steady_clock::now();
      const double us = std::chrono::duration<double, std::micro>(end - start).count();
      (tick.contact.in_contact() ? result.contact_tick_us : result.free_tick_us).push_back(us);
      if (!reference) continue;
      PathChecks& checks = *result.checks;
      const glm::vec3 tip = path.samples()[k].position_mm;
      const double depth = reference->depth_mm(tip);
      const float force = glm::length(tick.force_n);
      checks.max_force_n = std::max(checks.max_force_n, double(force));
      if (depth > pop_through_depth_mm && force == 0.0f) ++checks.pop_through_steps;
      if (depth > inward_force_depth_mm && glm::dot(tick.force_n, reference->outward_normal(tip)) < 0.0f) {
        ++checks.inward_force_steps;
      }
      if (tick.contact.in_contact()) {
        if (reference->depth_mm(tick.contact.point) > pop_through_depth_mm) ++checks.proxy_inside_steps;
        const double lag = glm::length(tick.contact.point - tip) - std::max(depth, 0.0);
        if (lag > stuck_lag_mm) stuck = true;
      }
    }
    if (stuck && result.checks) ++result.checks->stuck_cycles;
  }
  return result;
}

std::vector<SampledPath> sphere_slide_cycles(const BumpySphereReference& reference, const CycleShape& shape) {
  std::mt19937 rng(shape.seed);
  std::vector<SampledPath> cycles;
  const float radius = reference.radius_mm();
  for (int c = 0; c < shape.cycles; ++c) {
    const glm::vec3 u = random_direction(rng);
    const PressSlidePath nominal(press_slide(radius * u, u, random_tangent(rng, u), radius, shape));
    // The nominal path runs on the sphere of radius r; carry its height above that sphere over to
    // the bumpy surface along the same ray, so depths are measured on the real surface.
    std::vector<PathSample> samples(std::size_t(shape.ticks_per_cycle));
    for (int k = 0; k < shape.ticks_per_cycle; ++k) {
      const double time_s = k * 1e-3;
      const glm::dvec3 p(nominal.sample(time_s).position_mm);
      const glm::dvec3 direction = glm::normalize(p);
      const double depth = radius - glm::length(p);
      samples[std::size_t(k)] = {time_s, glm::vec3(direction * (reference.radius_at(direction) - depth))};
    }
    cycles.emplace_back(std::move(samples));
  }
  return cycles;
}

std::vector<PressSlide> aimed_press_slides(const Scene& scene, std::size_t object, const CycleShape& shape) {
  const SceneObject& target = scene.objects.at(object);
  Mesh mesh = target.mesh;
  if (mesh.normals.size() != mesh.positions.size()) compute_vertex_normals(mesh);
  const glm::vec3 centre = glm::vec3(target.transform * glm::vec4(bounds(mesh).center(), 1.0f));
  std::mt19937 rng(shape.seed);
  std::uniform_int_distribution<std::size_t> pick(0, mesh.positions.size() - 1);
  std::vector<PressSlide> slides;
  for (int c = 0; c < shape.cycles; ++c) {
    const std::size_t v = pick(rng);
    const glm::vec3 point = glm::vec3(target.transform * glm::vec4(mesh.positions[v], 1.0f));
    const glm::vec3 normal = glm::normalize(glm::mat3(target.transform) * mesh.normals[v]);
    const float curvature = std::max(glm::length(point - centre), 10.0f);
    slides.push_back(press_slide(point, normal, random_tangent(rng, normal), curvature, shape));
  }
  return slides;
}

std::vector<SampledPath> aimed_cycles(const Scene& scene, std::size_t object, const CycleShape& shape) {
  std::vector<SampledPath> cycles;
  for (const PressSlide& spec : aimed_press_slides(scene, object, shape)) {
    const PressSlidePath path(spec);
    std::vector<PathSample> samples(std::size_t(shape.ticks_per_cycle));
    for (int k = 0; k < shape.ticks_per_cycle; ++k) samples[std::size_t(k)] = {k * 1e-3, path.sample(k * 1e-3).position_mm};
    cycles.emplace_back(std::move(samples));
  }
  return cycles;
}

}  // namespace palpate::cli
