#include "palpate/testing/haptic_scenarios.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <random>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/haptics/haptic_pipeline.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate::testing {
namespace {

glm::dvec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  glm::dvec3 d;
  do d = {normal(rng), normal(rng), normal(rng)};
  while (glm::length(d) < 1e-3);
  return glm::normalize(d);
}

glm::dvec3 random_tangent(std::mt19937& rng, glm::dvec3 n) {
  glm::dvec3 t;
  do t = glm::cross(n, random_direction(rng));
  while (glm::length(t) < 1e-3);
  return glm::normalize(t);
}

// The timing of a press-slide: approach, slide, retract, rest.
struct Timing {
  int approach, slide, retract;
};

Timing timing(const CycleShape& shape) {
  const float press = shape.press_depth_mm;
  Timing t{int(std::ceil((shape.start_height_mm + press) / shape.speed_mm_per_s / tick_s)),
           int(std::ceil(shape.slide_length_mm / shape.speed_mm_per_s / tick_s)),
           int(std::ceil((shape.start_height_mm + press) / shape.speed_mm_per_s / tick_s))};
  if (t.approach + t.slide + t.retract > shape.ticks_per_cycle) {
    throw Error("haptic scenario: a cycle of " + std::to_string(shape.ticks_per_cycle) +
                " ticks is too short for its approach, slide and retract");
  }
  return t;
}

// The tip stays this much farther from any other part of the surface (farther than that from the
// pressed point) than from the pressed point.
constexpr double fold_clearance_mm = 1.0;

float depth_at(const CycleShape& shape, double s_mm) {
  return shape.press_depth_mm +
         shape.depth_amplitude_mm * float(std::sin(2.0 * std::numbers::pi * s_mm / shape.slide_length_mm));
}

// Rotates `v` by the smallest rotation that takes unit `from` to unit `to` (Rodrigues).
glm::dvec3 carry(const glm::dvec3& v, const glm::dvec3& from, const glm::dvec3& to) {
  const glm::dvec3 axis = glm::cross(from, to);
  const double s = glm::length(axis), c = glm::dot(from, to);
  if (s < 1e-12) return v;
  const glm::dvec3 k = axis / s;
  return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1.0 - c);
}

void add(std::vector<PathSample>& cycle, glm::dvec3 tip) {
  cycle.push_back({double(cycle.size()) * tick_s, glm::vec3(tip)});
}

std::vector<double> shorter_of(const std::vector<double>& first, const std::vector<double>& second,
                               const char* what) {
  if (first.size() != second.size()) {
    throw Error(std::string("shorter_ticks: the two runs differ in ") + what + " (" +
                std::to_string(first.size()) + " against " + std::to_string(second.size()) + ")");
  }
  std::vector<double> shorter(first.size());
  for (std::size_t i = 0; i < first.size(); ++i) shorter[i] = std::min(first[i], second[i]);
  return shorter;
}

}  // namespace

std::vector<SampledPath> sphere_slide(const BumpySphereOracle& oracle, const CycleShape& shape) {
  const Timing t = timing(shape);
  std::mt19937 rng(shape.seed);
  const double radius = oracle.radius_mm();
  std::vector<SampledPath> cycles;
  for (int c = 0; c < shape.cycles; ++c) {
    const glm::dvec3 up = random_direction(rng), along = random_tangent(rng, up);
    std::vector<PathSample> cycle;
    // On the mean sphere: the arc travelled and the depth under the bumpy surface, along the radius.
    for (int k = 0; k < shape.ticks_per_cycle; ++k) {
      double arc = 0.0, depth;
      if (k <= t.approach) {
        depth = -shape.start_height_mm + (shape.start_height_mm + shape.press_depth_mm) * k / t.approach;
      } else if (k <= t.approach + t.slide) {
        arc = shape.slide_length_mm * double(k - t.approach) / t.slide;
        depth = depth_at(shape, arc);
      } else {
        arc = shape.slide_length_mm;
        const double back = std::min(1.0, double(k - t.approach - t.slide) / t.retract);
        depth = depth_at(shape, arc) + (-shape.start_height_mm - depth_at(shape, arc)) * back;
      }
      const double angle = arc / radius;
      const glm::dvec3 u = std::cos(angle) * up + std::sin(angle) * along;
      add(cycle, u * (oracle.radius_at(u) - depth));
    }
    cycles.emplace_back(std::move(cycle));
  }
  return cycles;
}

std::vector<SampledPath> surface_press_slides(const Scene& scene, std::size_t object,
                                              const MeshOracle& oracle, const CycleShape& shape) {
  const Timing t = timing(shape);
  const SceneObject& target = scene.objects.at(object);
  if (target.mesh.positions_mm.empty())
    throw Error("haptic scenario: object '" + target.name + "' has no vertices");
  std::mt19937 rng(shape.seed);
  std::uniform_int_distribution<std::size_t> pick(0, target.mesh.positions_mm.size() - 1);
  const double step = shape.speed_mm_per_s * tick_s;
  std::vector<SampledPath> cycles;
  for (int attempts = 0; int(cycles.size()) < shape.cycles; ++attempts) {
    if (attempts > 100 * shape.cycles) {
      throw Error("haptic scenario: no vertex of '" + target.name + "' can be approached from outside");
    }
    const glm::dvec3 vertex(
        glm::vec3(target.transform * glm::vec4(target.mesh.positions_mm[pick(rng)], 1.0f)));
    const MeshOracle::Nearest start = oracle.nearest(vertex, 1.0);
    if (!start.found) continue;
    glm::dvec3 heading = random_tangent(rng, start.normal);
    const glm::dvec3 outside = start.point + start.normal * double(shape.start_height_mm);
    if (oracle.depth_mm(glm::vec3(outside)) > 0.0 ||
        oracle.segment_meets_surface(outside, start.point + start.normal * 0.05)) {
      continue;  // starts inside, or the approach runs through another fold first
    }
    std::vector<PathSample> cycle;
    glm::dvec3 p = start.point, n = start.normal;
    for (int k = 0; k <= t.approach; ++k) {
      const double height =
          shape.start_height_mm - (shape.start_height_mm + shape.press_depth_mm) * double(k) / t.approach;
      add(cycle, p + n * height);
    }
    for (int k = 1; k <= t.slide; ++k) {
      const MeshOracle::Nearest next = oracle.nearest(p + heading * step, 4.0 * step);
      if (!next.found) break;  // off the edge of an open surface
      const glm::dvec3 next_heading = carry(heading, n, next.normal);
      const double depth = depth_at(shape, shape.slide_length_mm * double(k) / t.slide);
      const glm::dvec3 tip = next.point - next.normal * depth;
      // Where the folds are thinner than the press, the tip would come nearer another part of the
      // surface than the one it presses; a god-object rightly stays on the first, and the checks could
      // no longer tell a stuck proxy from a faithful one. The slide ends before that.
      if (depth > 0.0 &&
          oracle.nearest_away(tip, depth + fold_clearance_mm, next.point, depth + fold_clearance_mm).found) {
        break;
      }
      heading = glm::normalize(next_heading - next.normal * glm::dot(next_heading, next.normal));
      p = next.point, n = next.normal;
      add(cycle, tip);
    }
    // Pull out along the normal as far as the way is clear (a sulcus wall may face it), at most the
    // start height.
    double clear = shape.start_height_mm;
    while (clear > 1.0 && oracle.segment_meets_surface(p + n * 0.05, p + n * clear)) clear *= 0.5;
    if (clear <= 1.0) continue;
    const double last_depth = -glm::dot(glm::dvec3(cycle.back().position_mm) - p, n);
    for (int k = 1; int(cycle.size()) < shape.ticks_per_cycle; ++k) {
      const double back = std::min(1.0, double(k) / t.retract);
      add(cycle, p - n * (last_depth + (-clear - last_depth) * back));
    }
    cycles.emplace_back(std::move(cycle));
  }
  return cycles;
}

ScenarioResult run_scenario(const Scene& scene, const Bvh& bvh, std::span<const SampledPath> cycles,
                            float max_force_n, const SurfaceOracle* oracle) {
  ScenarioResult result;
  std::size_t total = 0, longest = 0;
  for (const SampledPath& cycle : cycles) {
    total += cycle.samples().size();
    longest = std::max(longest, cycle.samples().size());
  }
  result.free_tick_us.reserve(total);
  result.contact_tick_us.reserve(total);
  result.free_between_us.reserve(total);
  result.contact_between_us.reserve(total);
  if (oracle) result.counts = ScenarioCounts{};
  DeviceLimits limits;
  limits.max_force_n = max_force_n;
  std::vector<TickResult> ticks(longest);
  std::vector<char> cut_short(longest);
  for (const SampledPath& cycle : cycles) {
    const std::vector<PathSample>& samples = cycle.samples();
    ScriptedDevice device(cycle, false, limits);
    HapticPipeline pipeline(device, scene, bvh);
    pipeline.reset_proxy(samples.front().position_mm);
    const std::size_t count = samples.size();
    // Time the whole cycle first, then check it, so that the checks do not cool the caches between ticks.
    for (std::size_t k = 0; k < count; ++k) {
      const auto start = std::chrono::steady_clock::now();
      ticks[k] = pipeline.tick(k, samples[k].time_s);
      const auto end = std::chrono::steady_clock::now();
      pipeline.prepare_next_tick();
      const auto prepared = std::chrono::steady_clock::now();
      cut_short[k] = pipeline.proxy_state().last_cut_short;
      const bool contact = ticks[k].contact.in_contact();
      (contact ? result.contact_tick_us : result.free_tick_us)
          .push_back(std::chrono::duration<double, std::micro>(end - start).count());
      (contact ? result.contact_between_us : result.free_between_us)
          .push_back(std::chrono::duration<double, std::micro>(prepared - end).count());
    }
    if (!oracle) continue;
    ScenarioCounts& counts = *result.counts;
    bool stuck = false;
    int away = 0;  // ticks in a row away from the local minimum
    for (std::size_t k = 0; k < count; ++k) {
      const TickResult& tick = ticks[k];
      const glm::vec3 tip = samples[k].position_mm;
      const double depth = oracle->depth_mm(tip);
      const float force = glm::length(tick.force_n);
      const bool capped = cut_short[k];
      counts.max_force_n = std::max(counts.max_force_n, double(force));
      counts.capped_ticks += capped;
      if (depth > pop_through_depth_mm && force == 0.0f) ++counts.pop_through_steps;
      if (!tick.contact.in_contact()) {
        away = 0;
        continue;
      }
      ++counts.contact_ticks;
      const glm::dvec3 proxy(tick.contact.point_mm);
      if (depth > inward_force_depth_mm &&
          glm::dot(glm::dvec3(tick.force_n), oracle->outward_normal(proxy)) < 0.0) {
        ++counts.inward_force_steps;
      }
      if (oracle->depth_mm(tick.contact.point_mm) > pop_through_depth_mm) ++counts.proxy_inside_steps;
      const double reachable = oracle->distance_near(glm::dvec3(tip), proxy, stuck_reach_mm);
      away = !capped && glm::distance(proxy, glm::dvec3(tip)) > reachable + stuck_lag_mm ? away + 1 : 0;
      if (away > stuck_grace_ticks || k + 1 == count) stuck = true;
    }
    if (stuck) ++counts.stuck_cycles;
  }
  return result;
}

ScenarioResult shorter_ticks(const ScenarioResult& first, const ScenarioResult& second) {
  ScenarioResult shorter;
  shorter.free_tick_us = shorter_of(first.free_tick_us, second.free_tick_us, "free ticks");
  shorter.contact_tick_us = shorter_of(first.contact_tick_us, second.contact_tick_us, "contact ticks");
  shorter.free_between_us = shorter_of(first.free_between_us, second.free_between_us, "free ticks");
  shorter.contact_between_us =
      shorter_of(first.contact_between_us, second.contact_between_us, "contact ticks");
  shorter.counts = first.counts;
  return shorter;
}

}  // namespace palpate::testing
