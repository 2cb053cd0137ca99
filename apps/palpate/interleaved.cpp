#include "interleaved.hpp"

#include <chrono>
#include <ctime>

namespace palpate::cli {
namespace {

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

}  // namespace

std::vector<Tally> measure_interleaved(const std::vector<std::function<void()>>& frames, double seconds,
                                       int rounds) {
  std::vector<Tally> tallies(frames.size());
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t v = 0; v < frames.size(); ++v) {
      Tally& tally = tallies[v];
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = process_cpu_seconds();
      double elapsed = 0.0;
      do {
        frames[v]();
        ++tally.frames;
        elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      } while (elapsed < seconds / rounds);
      tally.wall_s += elapsed;
      tally.cpu_s += process_cpu_seconds() - cpu_start;
    }
  }
  return tallies;
}

}  // namespace palpate::cli
