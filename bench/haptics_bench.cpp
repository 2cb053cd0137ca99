// Haptic core microbenchmarks: BVH build, and the haptic tick (device read, proxy step, spring-damper,
// device write) along the sphere-slide reference scenario, on bumpy spheres (radius 50 mm, +/-1.5 mm
// bumps) of the Table I sizes (22,952 and 53,021 triangles) and of 1M and 10M triangles.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/haptic_pipeline.hpp"
#include "palpate/haptics/loop_statistics.hpp"
#include "palpate/haptics/scripted_device.hpp"
#include "palpate/testing/haptic_scenarios.hpp"

namespace palpate {
namespace {

constexpr float radius_mm = 50.0f;
constexpr float bump_mm = 1.5f;

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

// The sphere-slide reference scenario (palpate/testing/haptic_scenarios.hpp), tick after tick through
// a HapticPipeline, round and round its cycles: approach, slide 1-4 mm deep, pull out, rest.
void BM_TickSphereSlide(benchmark::State& state) {
  const Prepared& p = prepared(std::size_t(state.range(0)));
  const testing::BumpySphereOracle oracle(radius_mm, bump_mm);
  std::vector<PathSample> joined;
  for (const SampledPath& cycle : testing::sphere_slide(oracle, {.cycles = 5, .seed = 1})) {
    for (const PathSample& sample : cycle.samples()) {
      joined.push_back({double(joined.size()) * testing::tick_s, sample.position_mm});
    }
  }
  ScriptedDevice device(SampledPath(std::move(joined)), true);
  HapticPipeline pipeline(device, p.scene, p.bvh);
  std::uint64_t tick = 0, contacts = 0;
  for (auto _ : state) {
    const TickResult result = pipeline.tick(tick, double(tick) * testing::tick_s);
    pipeline.prepare_next_tick();
    benchmark::DoNotOptimize(result);
    contacts += result.contact.in_contact();
    ++tick;
  }
  state.counters["contact_fraction"] = double(contacts) / double(state.iterations());
}

// Tick-time percentiles of the contact ticks of the sphere-slide scenario, each tick timed alone.
void BM_TickSphereSlidePercentiles(benchmark::State& state) {
  const Prepared& p = prepared(std::size_t(state.range(0)));
  const testing::BumpySphereOracle oracle(radius_mm, bump_mm);
  const std::vector<SampledPath> cycles = testing::sphere_slide(oracle, {.cycles = 10, .seed = 1});
  Percentiles us;
  for (auto _ : state) {
    testing::ScenarioResult result = testing::run_scenario(p.scene, p.bvh, cycles, 1e3f, nullptr);
    us = percentiles(result.contact_tick_us);
  }
  state.counters["p50_us"] = us.p50;
  state.counters["p99_us"] = us.p99;
  state.counters["p999_us"] = us.p999;
  state.counters["max_us"] = us.max;
}

// 22,952 and 53,021: the paper's Table I face counts; 1M and 10M: the large references.
#define PALPATE_SIZES Arg(22952)->Arg(53021)->Arg(1000000)->Arg(10000000)

BENCHMARK(BM_BvhBuild)->PALPATE_SIZES->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_TickSphereSlide)->PALPATE_SIZES;
BENCHMARK(BM_TickSphereSlidePercentiles)->PALPATE_SIZES->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace palpate
