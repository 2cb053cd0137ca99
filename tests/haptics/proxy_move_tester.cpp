#include "proxy_move_tester.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <random>
#include <string>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/haptics/force.hpp"
#include "palpate/haptics/proxy.hpp"
#include "palpate/testing/surface_oracle.hpp"

namespace palpate::test {
namespace {

// Sanitizer and debug builds run a tenth of the moves (never none): same code paths, bearable time.
#if defined(__SANITIZE_ADDRESS__) || !defined(NDEBUG)
constexpr int move_divisor = 10;
#else
constexpr int move_divisor = 1;
#endif

// What a step leaves: the proxy, its planes (with their multipliers) and the contact.
struct StepOutcome {
  ProxyState state;
  Contact contact;
  bool operator==(const StepOutcome& other) const {
    if (state.position_mm != other.state.position_mm ||
        state.constraint_count != other.state.constraint_count || contact.object != other.contact.object ||
        contact.triangle != other.contact.triangle || contact.point_mm != other.contact.point_mm ||
        contact.normal != other.contact.normal || contact.depth_mm != other.contact.depth_mm)
      return false;
    for (int i = 0; i < state.constraint_count; ++i) {
      const ProxyConstraint &a = state.constraints[std::size_t(i)],
                            &b = other.state.constraints[std::size_t(i)];
      if (a.normal != b.normal || a.offset_mm != b.offset_mm || a.multiplier_mm != b.multiplier_mm ||
          a.primitive != b.primitive)
        return false;
    }
    return true;
  }
};

StepOutcome step_from(const ProxyState& start, const Bvh& bvh, glm::vec3 hip, ProxyParams params, int cap) {
  StepOutcome outcome{start, {}};
  params.max_iterations = cap;
  outcome.contact = proxy_step(outcome.state, bvh, hip, params);
  return outcome;
}

struct Surface {  // a point on the mesh with its face normal and a tangent
  glm::dvec3 point, normal, tangent;
};

class MoveTester {
 public:
  MoveTester(const Scene& scene, std::uint32_t seed, const MoveOptions& options)
      : scene_(scene), bvh_(Bvh::build(scene)), reference_(scene), rng_(seed), options_(options) {
    const Bounds b = world_bounds(scene);
    lo_ = glm::dvec3(b.min_mm);
    hi_ = glm::dvec3(b.max_mm);
    const glm::dvec3 margin = 0.25 * (hi_ - lo_) + glm::dvec3(2.0);
    lo_ -= margin;
    hi_ += margin;
    if (options_.confine_xy > 0.0f) {
      lo_.x = lo_.y = -options_.confine_xy;
      hi_.x = hi_.y = options_.confine_xy;
    }
    hip_ = outside_start();
    state_.reset(glm::vec3(hip_));
  }

  void run() {
    while (ticks_ < options_.ticks && failures_ < 10) {
      switch (uniform_int(0, 7)) {
        case 0:
          jump();
          break;
        case 1:
          random_walk();
          break;
        case 2:
        case 3:
          press_and_slide();
          break;
        case 4:
          aim_at_feature();
          break;
        case 5:
          graze();
          break;
        case 6:
          fast_through();
          break;
        default:
          jitter();
          break;
      }
    }
    ::testing::Test::RecordProperty("ticks", ticks_);
    ::testing::Test::RecordProperty("contact_ticks", contact_ticks_);
    ::testing::Test::RecordProperty("release_checks", release_checks_);
    ::testing::Test::RecordProperty("capped_ticks", capped_ticks_);
    ::testing::Test::RecordProperty("came_back_ticks", came_back_ticks_);
    EXPECT_GE(ticks_, options_.ticks);
    // The moves really exercise contact and release.
    EXPECT_GT(contact_ticks_, ticks_ / 10);
    EXPECT_GT(release_checks_, 50);
    // The search converges within the segment cap, but for jumps of the tip right across the object.
    EXPECT_LE(capped_ticks_, options_.max_capped_fraction * ticks_);
  }

 private:
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  int uniform_int(int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng_); }
  glm::dvec3 random_point() { return {uniform(lo_.x, hi_.x), uniform(lo_.y, hi_.y), uniform(lo_.z, hi_.z)}; }
  glm::dvec3 random_direction() {
    glm::dvec3 d;
    do d = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    while (glm::dot(d, d) > 1.0 || glm::dot(d, d) < 1e-6);
    return glm::normalize(d);
  }
  glm::dvec3 confine(glm::dvec3 p) const {
    if (options_.confine_xy > 0.0f) {
      p.x = std::clamp(p.x, lo_.x, hi_.x);
      p.y = std::clamp(p.y, lo_.y, hi_.y);
    }
    return p;
  }
  glm::dvec3 outside_start() {
    if (options_.confine_xy > 0.0f) return {0.0, 0.0, options_.plate_top + 5.0};
    return {hi_.x, hi_.y, hi_.z};
  }

  Surface surface_point() {
    const SceneObject* object;
    do object = &scene_.objects[std::size_t(uniform_int(0, int(scene_.objects.size()) - 1))];
    while (!object->material.touchable);
    const Mesh& m = object->mesh;
    for (;;) {
      const std::size_t t = std::size_t(uniform_int(0, int(m.triangle_count()) - 1));
      const auto at = [&](int k) {
        return glm::dvec3(glm::vec3(object->transform *
                                    glm::vec4(m.positions_mm[m.indices[3 * t + std::size_t(k)]], 1.0f)));
      };
      const glm::dvec3 a = at(0), b = at(1), c = at(2);
      const glm::dvec3 n = glm::cross(b - a, c - a);
      if (glm::length(n) < 1e-12) continue;
      double u = uniform(0, 1), v = uniform(0, 1);
      if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
      const glm::dvec3 p = a + u * (b - a) + v * (c - a);
      if (options_.confine_xy > 0.0f &&
          (std::abs(p.x) > options_.confine_xy || std::abs(p.y) > options_.confine_xy))
        continue;
      return {p, glm::normalize(n), glm::normalize(b - a)};
    }
  }

  // One haptic tick with the HIP at `to`, and every check.
  void tick(glm::dvec3 to, double max_lag_mm = -1.0) {
    const ProxyState start = state_;
    const glm::dvec3 before = state_.position_mm;
    hip_ = confine(to);
    const Contact c = proxy_step(state_, bvh_, glm::vec3(hip_), params_);
    ++ticks_;
    contact_ticks_ += c.in_contact();
    capped_ticks_ += state_.last_cut_short;
    std::string came_back;
    if (state_.last_cut_short && state_.last_iterations < params_.max_iterations) {
      ++came_back_ticks_;
      came_back = differs_from_the_capped_search(start, bvh_, glm::vec3(hip_), params_, state_, c);
    }
    const glm::dvec3 p = state_.position_mm;
    const glm::dvec3 h(c.hip_mm);
    const auto fail = [&](const std::string& what) {
      ADD_FAILURE() << what << " at tick " << ticks_ << ": proxy (" << p.x << ", " << p.y << ", " << p.z
                    << ") hip (" << h.x << ", " << h.y << ", " << h.z << ") before (" << before.x << ", "
                    << before.y << ", " << before.z << ")";
      ++failures_;
    };
    if (!came_back.empty()) fail(came_back);
    if (reference_.inside(p)) fail("the proxy went inside a closed mesh");
    if (options_.plate_top != 0.0f && plate_side_ * p.z <= options_.plate_top)
      fail("the proxy went through the plate");
    if (c.in_contact()) {
      const glm::vec3 spring = c.point_mm - c.hip_mm;
      if (!(std::abs(glm::length(c.normal) - 1.0f) < 1e-4f)) fail("contact normal not unit");
      if (!(std::abs(glm::length(spring) - c.depth_mm) < 1e-4f)) fail("depth is not |SCP - HIP|");
      if (glm::length(spring) > 1e-3f && glm::dot(spring, c.normal) < 0.99f * glm::length(spring)) {
        fail("normal is not along SCP - HIP");
      }
      const ForceResult f = spring_damper(c, glm::vec3(0.0f), Material{.stiffness_n_per_mm = 1.0f}, 1e6f);
      if (f.invalid_input || glm::dot(f.force_n, c.normal) < 0.0f) fail("the force points into the surface");
    }
    if (ticks_ % options_.release_check_every == 0 && !reference_.inside(h) &&
        !reference_.segment_meets_surface(before, h)) {
      ++release_checks_;
      if (c.in_contact() || glm::length(p - h) > 1e-9)
        fail("the tip is outside with a clear path but not released");
    }
    if (max_lag_mm > 0.0 && c.in_contact() && c.depth_mm > max_lag_mm) fail("the proxy fell behind (stuck)");
  }

  void move_to(glm::dvec3 to, int steps, double max_lag_mm = -1.0) {
    const glm::dvec3 from = hip_;
    for (int i = 1; i <= steps; ++i) tick(from + (to - from) * (double(i) / steps), max_lag_mm);
  }

  void jump() { tick(random_point()); }

  void random_walk() {
    glm::dvec3 direction = random_direction();
    const double step = std::exp(uniform(std::log(0.002), std::log(0.5)));
    for (int i = uniform_int(50, 300); i > 0; --i) {
      direction = glm::normalize(direction + 0.3 * random_direction());
      glm::dvec3 next = hip_ + step * direction;
      if (next != glm::clamp(next, lo_, hi_)) direction = -direction, next = glm::clamp(next, lo_, hi_);
      tick(next);
    }
  }

  // Lift the tool off and put it down 1-3 mm in front of a face (outside), press 0-4 mm, slide 2-20 mm
  // with a varying depth, pull out.
  void press_and_slide() {
    const Surface s = surface_point();
    const glm::dvec3 approach = s.point + uniform(1.0, 3.0) * s.normal;
    if (reference_.inside(approach)) return;
    hip_ = approach;
    state_.reset(glm::vec3(hip_));
    plate_side_ = hip_.z > 0.0 ? 1.0 : -1.0;
    const double depth = uniform(0.0, 4.0);
    move_to(s.point - depth * s.normal, uniform_int(5, 40));
    const glm::dvec3 along = glm::normalize(glm::cross(s.normal, random_direction()));
    const double length = uniform(2.0, 20.0);
    const int steps = uniform_int(40, 400);
    const glm::dvec3 start = s.point;
    for (int i = 1; i <= steps; ++i) {
      const double f = double(i) / steps;
      const double d = depth * (0.6 + 0.4 * std::sin(6.0 * f));
      const double max_lag =
          options_.slide_lag_allowance_mm > 0.0 ? depth + options_.slide_lag_allowance_mm : -1.0;
      tick(start + length * f * along - d * s.normal, max_lag);
    }
    move_to(hip_ + uniform(2.0, 8.0) * s.normal, uniform_int(1, 20));
  }

  // Through a vertex or an edge midpoint of a random triangle, from outside to 0-3 mm past it.
  void aim_at_feature() {
    const Surface s = surface_point();
    // Snap the target onto a vertex or an edge of the triangle found by the BVH's closest point.
    const BvhHit near = bvh_.closest_point(s.point, 1.0);
    if (!near.hit()) return;
    const Bvh::Triangle& tri = bvh_.triangle(near.primitive);
    const int k = uniform_int(0, 2);
    const glm::dvec3 a(tri.vertices[std::size_t(k)]), b(tri.vertices[std::size_t((k + 1) % 3)]);
    const glm::dvec3 target = uniform_int(0, 1) ? a : 0.5 * (a + b);
    const glm::dvec3 in = glm::normalize(-s.normal + uniform(0.0, 1.2) * random_direction());
    move_to(target - uniform(1.0, 8.0) * in, uniform_int(1, 3));
    move_to(target + uniform(0.0, 3.0) * in, uniform_int(1, 20));
    move_to(target - uniform(1.0, 8.0) * in, uniform_int(1, 10));
  }

  // Skim along a face within +/-50 um of it, crossing edges.
  void graze() {
    const Surface s = surface_point();
    const glm::dvec3 along = glm::normalize(glm::cross(s.normal, random_direction()));
    move_to(s.point + 2.0 * s.normal, 2);
    const int steps = uniform_int(20, 200);
    const double length = uniform(1.0, 30.0);
    for (int i = 0; i <= steps; ++i) {
      const double f = double(i) / steps;
      tick(s.point + (f - 0.5) * length * along + uniform(-0.05, 0.05) * s.normal);
    }
  }

  // From well outside, straight through the middle to the other side, in 1-3 ticks.
  void fast_through() {
    const glm::dvec3 centre = 0.5 * (lo_ + hi_);
    const glm::dvec3 d = random_direction();
    const double reach = 0.5 * glm::length(hi_ - lo_);
    move_to(centre + reach * d, uniform_int(1, 3));
    move_to(centre - reach * d, uniform_int(1, 3));
  }

  // Tremble at a surface point by a micrometre: the proxy must not chatter through.
  void jitter() {
    const Surface s = surface_point();
    move_to(s.point + 1.0 * s.normal, 2);
    for (int i = uniform_int(20, 80); i > 0; --i) tick(s.point + 1e-3 * random_direction() - 1e-4 * s.normal);
  }

  const Scene& scene_;
  Bvh bvh_;
  testing::MeshOracle reference_;
  std::mt19937 rng_;
  MoveOptions options_;
  ProxyParams params_;
  ProxyState state_;
  glm::dvec3 lo_, hi_, hip_;
  double plate_side_ = 1.0;  // +1 above the plate, -1 below
  int ticks_ = 0, contact_ticks_ = 0, release_checks_ = 0, failures_ = 0, capped_ticks_ = 0,
      came_back_ticks_ = 0;
};

}  // namespace

std::string differs_from_the_capped_search(const ProxyState& start, const Bvh& bvh, glm::vec3 hip,
                                           const ProxyParams& params, const ProxyState& ended,
                                           const Contact& contact) {
  const int n = ended.last_iterations;
  // Capped at j <= n, the search runs j steps and never sees itself come back.
  std::vector<StepOutcome> capped_at(std::size_t(n) + 1);
  for (int j = 0; j <= n; ++j) capped_at[std::size_t(j)] = step_from(start, bvh, hip, params, j);
  // Step n started as the loop's first step did: capped at n + 1, the search ends as after that step.
  const StepOutcome one_more = step_from(start, bvh, hip, params, n + 1);
  int loop_start = -1;
  for (int j = 1; j <= n; ++j) {
    if (capped_at[std::size_t(j)] == one_more) loop_start = j - 1;
  }
  if (loop_start < 0) return "capped one step past coming back, the search ended off its loop";
  if (!(capped_at[std::size_t(n)] == capped_at[std::size_t(loop_start)]))
    return "the search came back to a step it had not started as before";
  const int loop_length = n - loop_start;
  const auto capped_at_loop_step = [&](int k) {
    return capped_at[std::size_t(loop_start + (k - loop_start) % loop_length)];
  };
  for (const int k : {n + 2, n + loop_length, n + 2 * loop_length + 1}) {
    if (!(step_from(start, bvh, hip, params, k) == capped_at_loop_step(k)))
      return "capped at " + std::to_string(k) + ", the search that came back ended off the cap's step";
  }
  // The tick itself, under its own cap.
  if (!(StepOutcome{ended, contact} == capped_at_loop_step(params.max_iterations)))
    return "capped at " + std::to_string(params.max_iterations) +
           ", the search that came back ended off the cap's step";
  return "";
}

void run_proxy_moves(const Scene& scene, std::uint32_t seed, MoveOptions options) {
  options.ticks = std::max(1, options.ticks / move_divisor);
  // Fewer moves, as many release checks: sample them as much more often.
  options.release_check_every = std::max(1, options.release_check_every / move_divisor);
  MoveTester(scene, seed, options).run();
}

}  // namespace palpate::test
