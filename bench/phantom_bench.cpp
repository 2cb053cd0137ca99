// Generation time of the default scene's phantoms (brain 68,856 + skin 90,207 = 159,063 vertices), which
// palpate builds whenever no scene file is given: the whole must stay well under a second. The plain
// sphere of the same size is the baseline the ratios are read against (same run, same machine).
#include <benchmark/benchmark.h>

#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"

namespace {

void count_vertices(benchmark::State& state, std::size_t vertices) {
  state.counters["vertices"] = double(vertices);
  state.counters["vertices_per_s"] =
      benchmark::Counter(double(vertices), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_BrainPhantom(benchmark::State& state) {
  const auto vertices = std::size_t(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(palpate::make_brain_phantom(vertices));
  count_vertices(state, vertices);
}
BENCHMARK(BM_BrainPhantom)->Arg(10000)->Arg(palpate::brain_phantom_vertices)->Unit(benchmark::kMillisecond);

void BM_SkinPhantom(benchmark::State& state) {
  const auto vertices = std::size_t(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(palpate::make_skin_phantom(vertices));
  count_vertices(state, vertices);
}
BENCHMARK(BM_SkinPhantom)->Arg(10000)->Arg(palpate::skin_phantom_vertices)->Unit(benchmark::kMillisecond);

// The default scene's two surfaces, as palpate builds them at start-up.
void BM_DefaultScenePhantoms(benchmark::State& state) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(palpate::make_brain_phantom());
    benchmark::DoNotOptimize(palpate::make_skin_phantom());
  }
  count_vertices(state, palpate::brain_phantom_vertices + palpate::skin_phantom_vertices);
}
BENCHMARK(BM_DefaultScenePhantoms)->Unit(benchmark::kMillisecond);

// Baseline: a plain sphere with the scene's vertex count (no folding, smoothing or flips).
void BM_SphereOfTheSceneSize(benchmark::State& state) {
  constexpr std::size_t vertices = palpate::brain_phantom_vertices + palpate::skin_phantom_vertices;
  for (auto _ : state) benchmark::DoNotOptimize(palpate::make_sphere(90.0f, vertices));
  count_vertices(state, vertices);
}
BENCHMARK(BM_SphereOfTheSceneSize)->Unit(benchmark::kMillisecond);

}  // namespace
