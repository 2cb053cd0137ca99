// Haptic core microbenchmarks: BVH build, and one haptic tick (proxy step + spring-damper) in free
// space and in sliding contact, on bumpy spheres (radius 50 mm, +/-1.5 mm bumps) of the Table I
// sizes (22,952 and 53,021 triangles) and of 1M and 10M triangles.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <memory>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/force.hpp"
#include "palpate/haptics/proxy.hpp"

namespace palpate {
namespace {

constexpr float radius_mm = 50.0f;
constexpr float bump_mm = 1.5f;
constexpr double tick_s = 1e-3;
constexpr double slide_speed_mm_per_s = 25.0;

struct Prepared {
  Scene scene;
  Bvh bvh;
};

// Meshes and trees are built once per size and shared by the benchmarks.
const Prepared& prepared(std::size_t triangles) {
  static std::map<std::size_t, std::unique_ptr<Prepared>> cache;
  auto& slot = cache[triangles];
  if (!slot) {
    slot = std::make_unique<Prepared>();
    slot->scene.objects.push_back(
        {"bumpy sphere", make_bumpy_sphere(radius_mm, bump_mm, triangles), glm::mat4(1.0f), {}, {}});
    slot->bvh = Bvh::build(slot->scene);
  }
  return *slot;
}

// A point on a tilted great circle of radius r, `s` mm along it.
glm::vec3 on_circle(double r, double s) {
  const double a = s / r;
  const glm::dvec3 u = glm::normalize(glm::dvec3(1, 0.3, 0.2)),
                   v = glm::normalize(glm::cross(u, glm::dvec3(0.1, 0.2, 1)));
  return glm::vec3(r * (std::cos(a) * u + std::sin(a) * v));
}

void BM_BvhBuild(benchmark::State& state) {
  const Prepared& p = prepared(std::size_t(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) {
    Bvh bvh = Bvh::build(p.scene);
    bytes = bvh.memory_bytes();
    benchmark::DoNotOptimize(bvh);
  }
  state.counters["triangles"] = double(p.bvh.triangle_count());
  state.counters["bytes_per_triangle"] = double(bytes) / double(p.bvh.triangle_count());
  state.counters["ns_per_triangle"] =
      benchmark::Counter(double(p.bvh.triangle_count()),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// One tick along a path: the HIP moves 25 um per tick (2.5 cm/s at 1 kHz) on a circle of radius
// `path_radius`: above the bumps (free) or 2.5 mm under the mean surface (sliding, 1-4 mm deep).
void run_ticks(benchmark::State& state, double path_radius) {
  const Prepared& p = prepared(std::size_t(state.range(0)));
  const Material material{.stiffness_n_per_mm = 1.0f, .damping_ns_per_m = 2.0f};
  const glm::vec3 velocity(0.0f);
  ProxyState proxy;
  // Approach from outside so a sliding proxy starts on the surface, not inside.
  proxy.reset(on_circle(radius_mm + 20.0, 0.0));
  for (int k = 0; k <= 100; ++k)
    proxy_step(proxy, p.bvh, on_circle(radius_mm + 20.0 - (20.0 + radius_mm - path_radius) * k / 100.0, 0.0));
  double s = 0.0;
  std::int64_t contacts = 0, iterations = 0;
  for (auto _ : state) {
    s += slide_speed_mm_per_s * tick_s;
    const Contact c = proxy_step(proxy, p.bvh, on_circle(path_radius, s));
    const ForceResult f = spring_damper(c, velocity, material, 1e3f);
    benchmark::DoNotOptimize(f);
    contacts += c.in_contact();
    iterations += proxy.last_iterations;
  }
  state.counters["contact_fraction"] = double(contacts) / double(state.iterations());
  state.counters["segments_per_tick"] = double(iterations) / double(state.iterations());
}

void BM_TickFree(benchmark::State& state) {
  run_ticks(state, radius_mm + bump_mm + 1.0);
}
void BM_TickSliding(benchmark::State& state) {
  run_ticks(state, radius_mm - 2.5);
}

// Tick-time percentiles over one slide of 4,000 ticks (~100 mm), timed one tick at a time.
void BM_TickSlidingPercentiles(benchmark::State& state) {
  const Prepared& p = prepared(std::size_t(state.range(0)));
  const Material material{.stiffness_n_per_mm = 1.0f, .damping_ns_per_m = 2.0f};
  std::vector<double> ns;
  ns.reserve(4000 * 64);
  for (auto _ : state) {
    ProxyState proxy;
    proxy.reset(on_circle(radius_mm + 20.0, 0.0));
    for (int k = 0; k <= 100; ++k)
      proxy_step(proxy, p.bvh, on_circle(radius_mm + 20.0 - 22.5 * k / 100.0, 0.0));
    for (int k = 0; k < 4000; ++k) {
      const glm::vec3 hip = on_circle(radius_mm - 2.5, slide_speed_mm_per_s * tick_s * k);
      const auto start = std::chrono::steady_clock::now();
      const Contact c = proxy_step(proxy, p.bvh, hip);
      const ForceResult f = spring_damper(c, glm::vec3(0.0f), material, 1e3f);
      const auto stop = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(f);
      ns.push_back(double(std::chrono::duration_cast<std::chrono::nanoseconds>(stop - start).count()));
    }
  }
  std::sort(ns.begin(), ns.end());
  const auto at = [&](double q) {
    return ns[std::min(ns.size() - 1, std::size_t(q * double(ns.size())))] / 1e3;
  };
  state.counters["p50_us"] = at(0.5);
  state.counters["p99_us"] = at(0.99);
  state.counters["p999_us"] = at(0.999);
  state.counters["max_us"] = ns.back() / 1e3;
}

// 22,952 and 53,021: the paper's Table I face counts; 1M and 10M: the large references.
#define PALPATE_SIZES Arg(22952)->Arg(53021)->Arg(1000000)->Arg(10000000)

BENCHMARK(BM_BvhBuild)->PALPATE_SIZES->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_TickFree)->PALPATE_SIZES;
BENCHMARK(BM_TickSliding)->PALPATE_SIZES;
BENCHMARK(BM_TickSlidingPercentiles)->PALPATE_SIZES->Iterations(5)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace palpate
