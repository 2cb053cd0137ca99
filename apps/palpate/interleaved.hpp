#pragma once
// Timing variants that run interleaved, in short slices round after round, so that a noisy machine
// slows them alike. Each frame function must end when its frame is done (glFinish or the like).
#include <functional>
#include <vector>

namespace palpate::cli {

struct Tally {
  int frames = 0;
  double wall_s = 0.0, cpu_s = 0.0;  // cpu: the process's CPU time, all threads
};

// Runs each of `frames` for seconds / rounds at a time, `rounds` times over; one tally per frame function.
std::vector<Tally> measure_interleaved(const std::vector<std::function<void()>>& frames, double seconds,
                                       int rounds);

}  // namespace palpate::cli
