#pragma once
// How well the haptic loop keeps its rate, in the spirit of GHOST's gstGetPhantomUpdateRate: the
// achieved rate over the last second, tick duration and period percentiles over a window of recent
// ticks, missed deadlines. The loop thread records; any thread takes a snapshot at any time without
// blocking it.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace palpate {

struct Percentiles {
  double p50 = 0.0, p99 = 0.0, p999 = 0.0, max = 0.0;
};

// Nearest-rank percentiles (the p-th is the smallest value with at least p% of the values at or
// below it). Reorders `values`; linear time, no allocation; all zero for an empty span.
Percentiles percentiles(std::span<double> values) noexcept;

struct LoopStatistics {
  double target_hz = 0.0;
  // Ticks that started in the second up to the latest tick's start; until the loop has run a second
  // (or when the window holds less than a second), ticks per second over the span the window holds.
  double achieved_hz = 0.0;
  std::uint64_t ticks = 0;                // since the loop was made
  std::uint64_t missed_deadlines = 0;     // ticks that ended after the end of their period
  std::uint64_t invalid_input_ticks = 0;  // ticks whose device input was not finite (zero force sent)
  std::size_t window_ticks = 0;           // how many recent ticks the percentiles cover
  Percentiles tick_us;                    // tick duration: device read to contact published
  Percentiles period_us;                  // start to start of consecutive ticks
  Percentiles period_error_us;            // |period - 1 / target_hz|
  // The window's periods in equal bins from 0.5 to 1.5 target periods; the first and last bins also
  // count the periods below and above that range. For a live histogram.
  static constexpr std::size_t histogram_bins = 40;
  std::array<std::uint32_t, histogram_bins> period_histogram{};
  // The window's periods in tick order, oldest first, us: for plots over time.
  std::vector<float> periods_us;
  // The host's steal time over the machine's CPUs since the loop's last start (host_steal.hpp), ms; -1
  // where the system does not say. Filled by HapticLoop::statistics.
  double steal_ms = -1.0;
};

// Single writer (the loop thread), any number of readers.
class LoopStatsRecorder {
 public:
  // Allocates the window (`window_ticks` >= 2 recent ticks, rounded up to a power of two).
  explicit LoopStatsRecorder(double target_hz, std::size_t window_ticks = 32768);

  // Loop thread, once per tick: no allocation, no lock, no system call. `first_of_run`: the tick
  // has no predecessor to measure a period from (the loop was just started).
  void record_tick(std::int64_t start_ns, std::int64_t end_ns, bool missed_deadline, bool invalid_input,
                   bool first_of_run) noexcept;

  // Any thread. Allocates a copy of the window; samples that the writer overwrites during the copy
  // are replaced by newer ones, each sample always whole.
  LoopStatistics snapshot() const;

 private:
  double target_hz_;
  std::int64_t target_period_ns_;
  std::size_t mask_;
  // Each entry packs (tick duration ns) << 32 | (period ns), saturated; no_period for none.
  std::unique_ptr<std::atomic<std::uint64_t>[]> samples_;
  // Writer-only: tick start times, for the rate over the last second.
  std::unique_ptr<std::int64_t[]> starts_;
  std::uint64_t rate_tail_ = 0;
  bool second_covered_ = false;  // this run has a tick a second or more before the latest
  std::int64_t last_start_ns_ = 0;
  std::uint64_t ticks_written_ = 0;
  std::uint64_t missed_written_ = 0;
  std::uint64_t invalid_written_ = 0;

  std::atomic<std::uint64_t> ticks_{0};
  std::atomic<std::uint64_t> missed_{0};
  std::atomic<std::uint64_t> invalid_{0};
  std::atomic<double> achieved_hz_{0.0};
};

}  // namespace palpate
