// The loop's schedule and statistics on a fake clock: every figure is worked out by hand from the
// scripted tick costs and wake-up delays.
#include "palpate/haptics/loop_statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/haptic_loop.hpp"

namespace palpate {
namespace {

constexpr std::int64_t us = 1'000;
constexpr std::int64_t ms = 1'000'000;

class FakeClock final : public LoopClock {
 public:
  std::int64_t now_ns() noexcept override { return now_; }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override {
    if (deadline_ns > now_) now_ = deadline_ns;
    if (wakes_ < late_wakes_.size()) now_ += late_wakes_[wakes_];
    ++wakes_;
  }
  void advance(std::int64_t ns) noexcept { now_ += ns; }
  std::vector<std::int64_t> late_wakes_;  // extra delay of the i-th wake-up

 private:
  std::int64_t now_ = 0;
  std::size_t wakes_ = 0;
};

// Each read costs the next scripted duration on the fake clock; remembers the times it was given.
class CostlyDevice final : public Device {
 public:
  CostlyDevice(FakeClock& clock, std::vector<std::int64_t> costs) : clock_(clock), costs_(std::move(costs)) {
    times_.reserve(costs_.size());
  }
  DeviceState read(double time_s) noexcept override {
    times_.push_back(time_s);
    clock_.advance(costs_[std::min(reads_++, costs_.size() - 1)]);
    return {};
  }
  void write(glm::vec3) noexcept override {}
  std::vector<double> times_;

 private:
  FakeClock& clock_;
  std::vector<std::int64_t> costs_;
  std::size_t reads_ = 0;
};

// A cube far from the device's resting point: every tick is in free space.
struct FarCube {
  Scene scene;
  Bvh bvh;
  FarCube() : scene(make_scene()), bvh(Bvh::build(scene)) {}
  static Scene make_scene() {
    Scene s;
    glm::mat4 far(1.0f);
    far[3] = glm::vec4(1000.0f, 0.0f, 0.0f, 1.0f);
    s.objects.push_back({"cube", make_box(glm::vec3(10.0f)), far, Material{}, {}});
    return s;
  }
};

TEST(PercentilesTest, NearestRank) {
  std::vector<double> values;
  for (int i = 1000; i >= 1; --i) values.push_back(i);
  const Percentiles p = percentiles(values);
  EXPECT_EQ(p.p50, 500.0);
  EXPECT_EQ(p.p99, 990.0);
  EXPECT_EQ(p.p999, 999.0);
  EXPECT_EQ(p.max, 1000.0);
  std::vector<double> one{7.0};
  EXPECT_EQ(percentiles(one).p50, 7.0);
  EXPECT_EQ(percentiles(one).p999, 7.0);
  EXPECT_EQ(percentiles(std::span<double>()).max, 0.0);
}

TEST(PercentilesTest, AgreesWithASortOnRandomData) {
  std::mt19937 rng(5);
  std::exponential_distribution<double> latency(1.0);
  for (const std::size_t n : {1u, 2u, 3u, 7u, 999u, 1000u, 1001u, 12345u}) {
    std::vector<double> values(n);
    for (double& v : values) v = latency(rng);
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    const auto nearest_rank = [&](double p) {
      const auto rank = static_cast<std::size_t>(std::ceil(p * double(n) - 1e-9));
      return sorted[std::max<std::size_t>(rank, 1) - 1];
    };
    const Percentiles p = percentiles(values);
    EXPECT_EQ(p.p50, nearest_rank(0.5)) << n;
    EXPECT_EQ(p.p99, nearest_rank(0.99)) << n;
    EXPECT_EQ(p.p999, nearest_rank(0.999)) << n;
    EXPECT_EQ(p.max, sorted.back()) << n;
  }
}

TEST(LoopStatisticsTest, ScheduleAndFiguresOnAFakeClock) {
  const FarCube cube;
  FakeClock clock;
  // Tick 2 overruns its 1 ms period by 1.5 ms.
  CostlyDevice device(clock, {100 * us, 100 * us, 2500 * us, 100 * us, 100 * us, 100 * us});
  HapticLoopParams params;
  params.rate_hz = 1000.0;
  HapticLoop loop(device, cube.scene, cube.bvh, params, &clock);
  loop.run_ticks(6);
  // Starts (ms): 1, 2, 3 (ends 5.5: missed), 5.5 (at once, on grid point 5), 6, 7.
  const std::vector<double> expected_times{0.001, 0.002, 0.003, 0.0055, 0.006, 0.007};
  ASSERT_EQ(device.times_.size(), expected_times.size());
  for (std::size_t i = 0; i < expected_times.size(); ++i)
    EXPECT_NEAR(device.times_[i], expected_times[i], 1e-12) << i;

  const LoopStatistics stats = loop.statistics();
  EXPECT_EQ(stats.ticks, 6u);
  EXPECT_EQ(stats.missed_deadlines, 1u);
  EXPECT_EQ(stats.invalid_input_ticks, 0u);
  EXPECT_EQ(stats.window_ticks, 6u);
  // Durations 100 x5 and 2500 us.
  EXPECT_DOUBLE_EQ(stats.tick_us.p50, 100.0);
  EXPECT_DOUBLE_EQ(stats.tick_us.p99, 2500.0);
  EXPECT_DOUBLE_EQ(stats.tick_us.max, 2500.0);
  // Periods 1000, 1000, 2500, 500, 1000 us; errors 0, 0, 1500, 500, 0.
  EXPECT_DOUBLE_EQ(stats.period_us.p50, 1000.0);
  EXPECT_DOUBLE_EQ(stats.period_us.max, 2500.0);
  EXPECT_DOUBLE_EQ(stats.period_error_us.p50, 0.0);
  EXPECT_DOUBLE_EQ(stats.period_error_us.p99, 1500.0);
  // Histogram bins of 25 us from 500 us: 1000 us lands in bin 20, 500 in bin 0, 2500 (beyond) in the last.
  std::array<std::uint32_t, LoopStatistics::histogram_bins> histogram{};
  histogram[20] = 3;
  histogram[0] = 1;
  histogram[LoopStatistics::histogram_bins - 1] = 1;
  EXPECT_EQ(stats.period_histogram, histogram);
  EXPECT_EQ(stats.periods_us, (std::vector<float>{1000, 1000, 2500, 500, 1000}));
  // Less than a second run: 5 periods in 6 ms.
  EXPECT_NEAR(stats.achieved_hz, 5.0 / 0.006, 1e-9);
  const Contact last = loop.latest().contact;
  EXPECT_EQ(last.tick, 5u);
  EXPECT_DOUBLE_EQ(last.time_s, 0.007);
  EXPECT_FALSE(last.in_contact());
}

TEST(LoopStatisticsTest, EveryMissedDeadlineIsCounted) {
  const FarCube cube;
  FakeClock clock;
  // Ticks 1, 3 and 4 overrun their 1 ms periods.
  CostlyDevice device(clock, {100 * us, 1500 * us, 100 * us, 1200 * us, 1100 * us, 100 * us});
  HapticLoop loop(device, cube.scene, cube.bvh, {}, &clock);
  loop.run_ticks(6);
  EXPECT_EQ(loop.statistics().missed_deadlines, 3u);
}

// A late tick makes one period long and the next short: both are off the target by the same amount.
TEST(LoopStatisticsTest, PeriodErrorIsTheDistanceFromTheTargetEitherWay) {
  const FarCube cube;
  FakeClock clock;
  clock.late_wakes_ = {0, 300 * us, 0, 300 * us, 0, 0};
  CostlyDevice device(clock, {50 * us});
  HapticLoop loop(device, cube.scene, cube.bvh, {}, &clock);
  loop.run_ticks(6);
  // Starts (ms): 1, 2.3, 3, 4.3, 5, 6: periods 1300, 700, 1300, 700, 1000; errors 300 x4 and 0.
  const LoopStatistics stats = loop.statistics();
  EXPECT_DOUBLE_EQ(stats.period_us.p50, 1000.0);
  EXPECT_DOUBLE_EQ(stats.period_error_us.p50, 300.0);  // nearest rank 3 of 0, 300, 300, 300, 300
  EXPECT_DOUBLE_EQ(stats.period_error_us.max, 300.0);
}

TEST(LoopStatisticsTest, LateWakeUpsShowInThePeriodNotAsMisses) {
  const FarCube cube;
  FakeClock clock;
  clock.late_wakes_ = {0, 0, 300 * us};  // the third wake-up is 300 us late
  CostlyDevice device(clock, {50 * us});
  HapticLoop loop(device, cube.scene, cube.bvh, {}, &clock);
  loop.run_ticks(5);
  const LoopStatistics stats = loop.statistics();
  EXPECT_EQ(stats.missed_deadlines, 0u);
  // Starts (ms): 1, 2, 3.3, 4, 5: periods 1000, 1300, 700, 1000; errors 0, 300, 300, 0.
  EXPECT_DOUBLE_EQ(stats.period_us.max, 1300.0);
  EXPECT_DOUBLE_EQ(stats.period_us.p50, 1000.0);
  EXPECT_DOUBLE_EQ(stats.period_error_us.p50, 0.0);  // nearest rank 2 of 0, 0, 300, 300
  EXPECT_DOUBLE_EQ(stats.period_error_us.p99, 300.0);
  EXPECT_DOUBLE_EQ(stats.period_error_us.max, 300.0);
  EXPECT_DOUBLE_EQ(stats.tick_us.max, 50.0);
}

TEST(LoopStatisticsTest, AchievedRateCountsTheLastSecond) {
  const FarCube cube;
  {
    FakeClock clock;
    CostlyDevice device(clock, {10 * us});
    HapticLoop loop(device, cube.scene, cube.bvh, {}, &clock);
    loop.run_ticks(2000);
    EXPECT_DOUBLE_EQ(loop.statistics().achieved_hz, 1000.0);
  }
  FakeClock clock;
  // Tick 2000 (at 2001 ms) stalls for 100.5 ms: the next starts at once, then the grid goes on at
  // 2102 ms; 100 periods are lost.
  std::vector<std::int64_t> costs(2500, 10 * us);
  costs[2000] = 100'500 * us;
  CostlyDevice device(clock, costs);
  HapticLoop loop(device, cube.scene, cube.bvh, {}, &clock);
  loop.run_ticks(2500);
  EXPECT_NEAR(device.times_[2001], 2.1015, 1e-12);
  EXPECT_NEAR(device.times_[2002], 2.102, 1e-12);
  // (1599, 2599] ms holds the starts 1600..2001 (402 ticks), 2101.5 and 2102..2599 (498).
  const LoopStatistics stats = loop.statistics();
  EXPECT_EQ(stats.ticks, 2500u);
  EXPECT_EQ(stats.missed_deadlines, 1u);
  EXPECT_DOUBLE_EQ(stats.achieved_hz, 901.0);
}

TEST(LoopStatsRecorderTest, RateOverTheLastSecondAfterAStall) {
  LoopStatsRecorder recorder(1000.0);
  // Ticks at 1..2000 ms, one at 2001 ms that ends at 2101.5, then 2101.5 and 2102..2599 ms.
  std::int64_t start = 0;
  for (int k = 0; k < 2000; ++k) {
    start = (k + 1) * ms;
    recorder.record_tick(start, start + 10 * us, false, false, k == 0);
  }
  recorder.record_tick(2001 * ms, 2101 * ms + 500 * us, true, false, false);
  recorder.record_tick(2101 * ms + 500 * us, 2101 * ms + 510 * us, false, false, false);
  for (int k = 2002; k < 2500; ++k) {
    start = (k + 100) * ms;
    recorder.record_tick(start, start + 10 * us, false, false, false);
  }
  // (1599, 2599] ms holds the starts 1600..2001 (402 ticks), 2101.5 and 2102..2599 (498).
  const LoopStatistics stats = recorder.snapshot();
  EXPECT_DOUBLE_EQ(stats.achieved_hz, 901.0);
  EXPECT_EQ(stats.missed_deadlines, 1u);
  EXPECT_EQ(stats.ticks, 2500u);
  EXPECT_DOUBLE_EQ(stats.period_us.max, 100'500.0);
  EXPECT_DOUBLE_EQ(stats.period_error_us.max, 99'500.0);
}

TEST(LoopStatsRecorderTest, WindowSmallerThanASecondGivesTheRateOverItsSpan) {
  LoopStatsRecorder recorder(10'000.0, 1000);  // rounded up to 1024 ticks, 102.4 ms at 10 kHz
  for (int k = 0; k < 3000; ++k) {
    const std::int64_t start = k * 100 * us;
    recorder.record_tick(start, start + 5 * us, false, k == 7, k == 0);
  }
  const LoopStatistics stats = recorder.snapshot();
  EXPECT_EQ(stats.window_ticks, 1024u);
  EXPECT_NEAR(stats.achieved_hz, 10'000.0, 1e-6);
  EXPECT_EQ(stats.invalid_input_ticks, 1u);
  EXPECT_DOUBLE_EQ(stats.period_us.p50, 100.0);
  EXPECT_DOUBLE_EQ(stats.period_error_us.max, 0.0);
  EXPECT_DOUBLE_EQ(stats.tick_us.p999, 5.0);
}

TEST(LoopStatsRecorderTest, RejectsANonPositiveRate) {
  EXPECT_THROW(LoopStatsRecorder{0.0}, Error);
  EXPECT_THROW(LoopStatsRecorder{-5.0}, Error);
}

}  // namespace
}  // namespace palpate
