#include "haptic_scenarios.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>
#include <string>

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

ScenarioResult run_cycles(const Scene& scene, const Bvh& bvh, const std::vector<SampledPath>& cycles,
                          float max_force_n, const SurfaceReference* reference) {
  ScenarioResult result;
  std::size_t total = 0, longest = 0;
  for (const SampledPath& path : cycles) {
    total += path.samples().size();
    longest = std::max(longest, path.samples().size());
  }
  result.free_tick_us.reserve(total);
  result.contact_tick_us.reserve(total);
  if (reference) result.checks = PathChecks{};
  DeviceLimits limits;
  limits.max_force_n = max_force_n;
  std::vector<TickResult> ticks(longest);
  for (const SampledPath& path : cycles) {
    ScriptedDevice device(path, false, limits);
    HapticPipeline pipeline(device, scene, bvh);
    pipeline.reset_proxy(path.samples().front().position_mm);
    const std::size_t count = path.samples().size();
    // Time the whole cycle first, then check it, so the checks do not cool the caches between ticks.
    for (std::size_t k = 0; k < count; ++k) {
      const auto start = std::chrono::steady_clock::now();
      ticks[k] = pipeline.tick(k, path.samples()[k].time_s);
      const auto end = std::chrono::steady_clock::now();
      const double us = std::chrono::duration<double, std::micro>(end - start).count();
      (ticks[k].contact.in_contact() ? result.contact_tick_us : result.free_tick_us).push_back(us);
    }
    if (!reference) continue;
    PathChecks& checks = *result.checks;
    bool stuck = false;
    for (std::size_t k = 0; k < count; ++k) {
      const TickResult& tick = ticks[k];
      const glm::vec3 tip = path.samples()[k].position_mm;
      const double depth = reference->depth_mm(tip);
      const float force = glm::length(tick.force_n);
      checks.max_force_n = std::max(checks.max_force_n, double(force));
      if (depth > pop_through_depth_mm && force == 0.0f) ++checks.pop_through_steps;
      if (depth > inward_force_depth_mm && reference->pushes_inward(tip, tick.force_n))
        ++checks.inward_force_steps;
      if (tick.contact.in_contact()) {
        if (reference->depth_mm(tick.contact.point) > pop_through_depth_mm) ++checks.proxy_inside_steps;
        const double lag = glm::length(tick.contact.point - tip) - std::max(depth, 0.0);
        if (lag > stuck_lag_mm && depth < reference->depth_limit_mm()) stuck = true;
      }
    }
    if (stuck) ++checks.stuck_cycles;
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

std::vector<PressSlide> aimed_press_slides(const Scene& scene, std::size_t object, const CycleShape& shape,
                                           const SurfaceReference* reference) {
  const SceneObject& target = scene.objects.at(object);
  std::mt19937 rng(shape.seed);
  std::uniform_int_distribution<std::size_t> pick(0, target.mesh.positions.size() - 1);
  std::vector<PressSlide> slides;
  for (int attempts = 0; int(slides.size()) < shape.cycles; ++attempts) {
    if (attempts > 1000 * shape.cycles)
      throw Error("haptic scenario: no vertex of '" + target.name + "' can be approached from outside");
    const PressSlide aimed = aim_press_slide(target, pick(rng), glm::vec3(0.0f));
    const PressSlide slide =
        press_slide(aimed.surface_point_mm, aimed.normal, random_tangent(rng, aimed.normal),
                    std::max(aimed.curvature_radius_mm, 10.0f), shape);
    if (reference && reference->depth_mm(PressSlidePath(slide).sample(0.0).position_mm) > 0.0) continue;
    slides.push_back(slide);
  }
  return slides;
}

std::vector<SampledPath> aimed_cycles(const Scene& scene, std::size_t object, const CycleShape& shape,
                                      const SurfaceReference* reference) {
  std::vector<SampledPath> cycles;
  for (const PressSlide& spec : aimed_press_slides(scene, object, shape, reference)) {
    const PressSlidePath path(spec);
    std::vector<PathSample> samples(std::size_t(shape.ticks_per_cycle));
    for (int k = 0; k < shape.ticks_per_cycle; ++k)
      samples[std::size_t(k)] = {k * 1e-3, path.sample(k * 1e-3).position_mm};
    cycles.emplace_back(std::move(samples));
  }
  return cycles;
}

}  // namespace palpate::cli
