#pragma once
// The haptic loop's time source, injectable so that its schedule and statistics can be tested on a
// fake clock. Times are integer nanoseconds on a monotonic scale with an arbitrary origin.
#include <cstdint>

namespace palpate {

class LoopClock {
 public:
  virtual ~LoopClock() = default;
  virtual std::int64_t now_ns() noexcept = 0;
  // Returns at `deadline_ns` or as soon after it as possible (at once when it has passed).
  virtual void sleep_until_ns(std::int64_t deadline_ns) noexcept = 0;
};

// CLOCK_MONOTONIC. Sleeps with clock_nanosleep(TIMER_ABSTIME) until `spin_ns` before the deadline,
// then spins on the clock: the sleep's wake-up latency (tens of microseconds on a normal kernel)
// lands in the spin instead of in the period.
class MonotonicClock final : public LoopClock {
 public:
  explicit MonotonicClock(std::int64_t spin_ns = 100'000) noexcept : spin_ns_(spin_ns) {}
  std::int64_t now_ns() noexcept override;
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override;
  std::int64_t spin_ns() const noexcept { return spin_ns_; }

 private:
  std::int64_t spin_ns_;
};

}  // namespace palpate
