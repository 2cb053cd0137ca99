// Microbenchmarks of the haptic loop's own parts: the latest-value channel, the statistics
// recorder, and one whole pipeline tick sliding on a bumpy sphere.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "palpate/core/bvh.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/haptic_pipeline.hpp"
#include "palpate/haptics/latest.hpp"
#include "palpate/haptics/loop_statistics.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate {
namespace {

void BM_LatestStoreContact(benchmark::State& state) {
  Latest<Contact> channel;
  Contact contact;
  for (auto _ : state) {
    ++contact.tick;
    channel.store(contact);
  }
  benchmark::DoNotOptimize(channel.version());
}
BENCHMARK(BM_LatestStoreContact);

void BM_LatestLoadContact(benchmark::State& state) {
  Latest<Contact> channel;
  channel.store(Contact{});
  for (auto _ : state) benchmark::DoNotOptimize(channel.load());
}
BENCHMARK(BM_LatestLoadContact);

void BM_LoopStatsRecordTick(benchmark::State& state) {
  LoopStatsRecorder recorder(1000.0);
  std::int64_t start = 0;
  for (auto _ : state) {
    start += 1'000'000;
    recorder.record_tick(start, start + 1500, false, false, start == 1'000'000);
  }
}
BENCHMARK(BM_LoopStatsRecordTick);

// One tick (device read, proxy step, spring-damper, device write) sliding on a bumpy sphere of
// radius 50 mm with the given triangle count, 1 ms of path per tick.
void BM_PipelineTickSlidingOnBumpySphere(benchmark::State& state) {
  Scene scene;
  SceneObject sphere;
  sphere.name = "bumpy-sphere";
  sphere.mesh = make_bumpy_sphere(50.0f, 1.5f, std::size_t(state.range(0)));
  scene.objects.push_back(std::move(sphere));
  const Bvh bvh = Bvh::build(scene);
  PressSlide spec;
  spec.surface_point_mm = {0.0f, 0.0f, 50.0f};
  spec.normal = {0.0f, 0.0f, 1.0f};
  spec.slide_direction = {1.0f, 0.3f, 0.0f};
  spec.curvature_radius_mm = 50.0f;
  ScriptedDevice device(PressSlidePath(spec), true);
  HapticPipeline pipeline(device, scene, bvh);
  std::uint64_t tick = 0;
  for (auto _ : state) {
    const TickResult result = pipeline.tick(tick, double(tick) * 1e-3);
    benchmark::DoNotOptimize(result);
    ++tick;
  }
  state.SetLabel(std::to_string(bvh.triangle_count()) + " triangles");
}
BENCHMARK(BM_PipelineTickSlidingOnBumpySphere)->Arg(22'952)->Arg(1'000'000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace palpate
