// Microbenchmarks of the haptic loop's own parts: the latest-value channel and the statistics recorder
// (the whole tick is in haptics_bench.cpp).
#include <benchmark/benchmark.h>

#include <cstdint>

#include "palpate/haptics/haptic_pipeline.hpp"
#include "palpate/haptics/latest.hpp"
#include "palpate/haptics/loop_statistics.hpp"

namespace palpate {
namespace {

// What the haptic loop publishes each tick.
void BM_LatestStoreTickResult(benchmark::State& state) {
  Latest<TickResult> channel;
  TickResult result;
  for (auto _ : state) {
    ++result.contact.tick;
    channel.store(result);
  }
  benchmark::DoNotOptimize(channel.version());
}
BENCHMARK(BM_LatestStoreTickResult);

void BM_LatestLoadTickResult(benchmark::State& state) {
  Latest<TickResult> channel;
  channel.store(TickResult{});
  for (auto _ : state) benchmark::DoNotOptimize(channel.load());
}
BENCHMARK(BM_LatestLoadTickResult);

void BM_LoopStatsRecordTick(benchmark::State& state) {
  LoopStatsRecorder recorder(1000.0);
  std::int64_t start = 0;
  for (auto _ : state) {
    start += 1'000'000;
    recorder.record_tick(start, start + 1500, false, false, start == 1'000'000);
  }
}
BENCHMARK(BM_LoopStatsRecordTick);

}  // namespace
}  // namespace palpate
