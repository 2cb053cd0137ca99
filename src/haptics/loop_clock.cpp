#include "palpate/haptics/loop_clock.hpp"

#include <cerrno>
#include <ctime>

namespace palpate {
namespace {

timespec to_timespec(std::int64_t ns) noexcept {
  return timespec{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
}

}  // namespace

std::int64_t MonotonicClock::now_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return std::int64_t(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

void MonotonicClock::sleep_until_ns(std::int64_t deadline_ns) noexcept {
  const std::int64_t wake_ns = deadline_ns - spin_ns_;
  if (now_ns() < wake_ns) {
    const timespec wake = to_timespec(wake_ns);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) == EINTR) {
    }
  }
  while (now_ns() < deadline_ns) {
  }
}

}  // namespace palpate
