// Loading speed of palpate's own output formats at the size of the paper's default scene
// (brain 68,856 + skin 90,207 = 159,063 vertices, here as one closed sphere).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "palpate/core/load.hpp"
#include "palpate/core/shapes.hpp"

namespace {

std::filesystem::path scene_sized_file(const char* extension) {
  const auto file =
      std::filesystem::temp_directory_path() / (std::string("palpate_bench_159063") + extension);
  if (!std::filesystem::exists(file)) palpate::save_mesh(palpate::make_sphere(90.0f, 159063), file);
  return file;
}

void BM_LoadPly159k(benchmark::State& state) {
  const auto file = scene_sized_file(".ply");
  for (auto _ : state) benchmark::DoNotOptimize(palpate::load_mesh(file));
  state.counters["vertices"] = 159063;
}
BENCHMARK(BM_LoadPly159k)->Unit(benchmark::kMillisecond);

void BM_LoadVrml159k(benchmark::State& state) {
  const auto file = scene_sized_file(".wrl");
  for (auto _ : state) benchmark::DoNotOptimize(palpate::load_mesh(file));
  state.counters["vertices"] = 159063;
}
BENCHMARK(BM_LoadVrml159k)->Unit(benchmark::kMillisecond);

}  // namespace
