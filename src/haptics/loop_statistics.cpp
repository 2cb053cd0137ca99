#include "palpate/haptics/loop_statistics.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "palpate/core/error.hpp"

namespace palpate {
namespace {

constexpr std::uint32_t no_period = std::numeric_limits<std::uint32_t>::max();
constexpr std::int64_t one_second_ns = 1'000'000'000;

std::uint32_t saturate(std::int64_t ns) noexcept {
  return static_cast<std::uint32_t>(std::clamp<std::int64_t>(ns, 0, no_period - 1));
}

// Nearest rank ceil(permille / 1000 * n), in integers so that 99.9 % of 1000 is exactly rank 999.
std::size_t rank_index(std::size_t count, std::size_t permille) noexcept {
  return std::clamp<std::size_t>((permille * count + 999) / 1000, 1, count) - 1;
}

}  // namespace

Percentiles percentiles(std::span<double> values) noexcept {
  if (values.empty()) return {};
  // Selection instead of a sort: linear time, so a GUI can poll the statistics every frame.
  const std::size_t i999 = rank_index(values.size(), 999), i99 = rank_index(values.size(), 990),
                    i50 = rank_index(values.size(), 500);
  const auto max = std::max_element(values.begin(), values.end());
  std::iter_swap(max, values.end() - 1);
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(i999), values.end() - 1);
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(i99),
                   values.begin() + std::ptrdiff_t(i999));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(i50),
                   values.begin() + std::ptrdiff_t(i99));
  return {values[i50], values[i99], values[i999], values.back()};
}

LoopStatsRecorder::LoopStatsRecorder(double target_hz, std::size_t window_ticks)
    : target_hz_(target_hz),
      target_period_ns_(std::llround(1e9 / target_hz)),
      mask_(std::bit_ceil(std::max<std::size_t>(window_ticks, 2)) - 1),
      samples_(std::make_unique<std::atomic<std::uint64_t>[]>(mask_ + 1)),
      starts_(std::make_unique<std::int64_t[]>(mask_ + 1)) {
  if (!(std::isfinite(target_hz) && target_hz > 0.0)) {
    throw Error("loop statistics: target rate must be positive, got " + std::to_string(target_hz) + " Hz");
  }
}

void LoopStatsRecorder::record_tick(std::int64_t start_ns, std::int64_t end_ns, bool missed_deadline,
                                    bool invalid_input, bool first_of_run) noexcept {
  const std::uint64_t k = ticks_written_;
  const bool has_period = k > 0 && !first_of_run;
  const std::uint32_t period = has_period ? saturate(start_ns - last_start_ns_) : no_period;
  samples_[k & mask_].store(std::uint64_t(saturate(end_ns - start_ns)) << 32 | period,
                            std::memory_order_relaxed);

  // Rate: the ring of start times holds this run's ticks rate_tail_..k; drop those a second old.
  if (first_of_run) {
    rate_tail_ = k;
    second_covered_ = false;
  }
  if (k - rate_tail_ > mask_) rate_tail_ = k - mask_;  // the slot about to be written
  starts_[k & mask_] = start_ns;
  while (rate_tail_ < k && starts_[rate_tail_ & mask_] <= start_ns - one_second_ns) {
    ++rate_tail_;
    second_covered_ = true;
  }
  const std::uint64_t in_window = k - rate_tail_ + 1;
  const bool ring_full = in_window == mask_ + 1;
  double hz = 0.0;
  if (second_covered_ && !ring_full) {
    hz = double(in_window);  // ticks that started in (start - 1 s, start]
  } else if (const std::int64_t span_ns = start_ns - starts_[rate_tail_ & mask_]; span_ns > 0) {
    hz = double(in_window - 1) * 1e9 / double(span_ns);
  }
  achieved_hz_.store(hz, std::memory_order_relaxed);

  last_start_ns_ = start_ns;
  ticks_written_ = k + 1;
  if (missed_deadline) missed_.store(++missed_written_, std::memory_order_relaxed);
  if (invalid_input) invalid_.store(++invalid_written_, std::memory_order_relaxed);
  ticks_.store(ticks_written_, std::memory_order_release);
}

LoopStatistics LoopStatsRecorder::snapshot() const {
  LoopStatistics stats;
  stats.target_hz = target_hz_;
  stats.ticks = ticks_.load(std::memory_order_acquire);
  stats.missed_deadlines = missed_.load(std::memory_order_relaxed);
  stats.invalid_input_ticks = invalid_.load(std::memory_order_relaxed);
  stats.achieved_hz = achieved_hz_.load(std::memory_order_relaxed);
  const std::uint64_t count = std::min<std::uint64_t>(stats.ticks, mask_ + 1);
  stats.window_ticks = count;
  std::vector<double> ticks_us, periods_us, errors_us;
  ticks_us.reserve(count);
  periods_us.reserve(count);
  errors_us.reserve(count);
  for (std::uint64_t i = stats.ticks - count; i < stats.ticks; ++i) {
    const std::uint64_t packed = samples_[i & mask_].load(std::memory_order_relaxed);
    ticks_us.push_back(double(packed >> 32) * 1e-3);
    const auto period = static_cast<std::uint32_t>(packed);
    if (period == no_period) continue;
    periods_us.push_back(double(period) * 1e-3);
    const double bin =
        (double(period) / double(target_period_ns_) - 0.5) * double(LoopStatistics::histogram_bins);
    ++stats.period_histogram[std::size_t(std::clamp(bin, 0.0, double(LoopStatistics::histogram_bins - 1)))];
    errors_us.push_back(std::abs(double(std::int64_t(period) - target_period_ns_)) * 1e-3);
  }
  stats.periods_us.assign(periods_us.begin(), periods_us.end());
  stats.tick_us = percentiles(ticks_us);
  stats.period_us = percentiles(periods_us);
  stats.period_error_us = percentiles(errors_us);
  return stats;
}

}  // namespace palpate
