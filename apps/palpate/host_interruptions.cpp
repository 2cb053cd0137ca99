#include "host_interruptions.hpp"

#include <algorithm>
#include <chrono>

namespace palpate::cli {

HostInterruptions measure_host_interruptions(double seconds) {
  using Clock = std::chrono::steady_clock;
  HostInterruptions result;
  const Clock::time_point start = Clock::now(), end = start + std::chrono::duration_cast<Clock::duration>(
                                                                  std::chrono::duration<double>(seconds));
  long long over_5 = 0, over_20 = 0;
  double lost_us = 0.0;
  Clock::time_point last = start, now = start;
  while (now < end) {
    now = Clock::now();
    const double gap_us = std::chrono::duration<double, std::micro>(now - last).count();
    if (gap_us >= 5.0) {
      ++over_5;
      over_20 += gap_us >= 20.0;
      lost_us += gap_us;
      result.longest_us = std::max(result.longest_us, gap_us);
    }
    last = now;
  }
  result.seconds = std::chrono::duration<double>(now - start).count();
  result.per_s_over_5us = double(over_5) / result.seconds;
  result.per_s_over_20us = double(over_20) / result.seconds;
  result.lost_us_per_s = lost_us / result.seconds;
  return result;
}

}  // namespace palpate::cli
