#pragma once
// The haptic loop: a thread of its own that runs a HapticPipeline tick at a fixed rate on absolute
// deadlines and publishes each tick's Contact through a Latest<Contact> that any thread may read.
//
// Schedule: period k starts at a deadline on the grid origin + k / rate. The thread sleeps until the
// deadline (clock_nanosleep TIMER_ABSTIME, then a short spin), runs the tick, and records its start,
// duration and period. A tick that ends after the end of its period is a missed deadline; the next
// tick then starts at once, on the latest grid point already passed, so a late tick never causes a
// burst of catch-up ticks (lost periods show in the achieved rate).
//
// SCHED_FIFO is requested when the thread starts; where it is not permitted, start() writes one line
// to stderr and the loop runs at normal priority. Inside the loop nothing allocates, locks, logs or
// does I/O; tests/concurrency/haptic_loop_test.cpp counts operator new calls on the loop thread.
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>

#include "palpate/core/bvh.hpp"
#include "palpate/core/contact.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/device.hpp"
#include "palpate/haptics/device_transform.hpp"
#include "palpate/haptics/haptic_pipeline.hpp"
#include "palpate/haptics/latest.hpp"
#include "palpate/haptics/loop_clock.hpp"
#include "palpate/haptics/loop_statistics.hpp"
#include "palpate/haptics/proxy.hpp"

namespace palpate {

struct HapticLoopParams {
  double rate_hz = 1000.0;          // target tick rate, Hz, in [1, 100000]
  DeviceTransform device_to_scene;  // device frame to scene (workspace scaling + rigid)
  ProxyParams proxy;
  bool realtime_priority = true;          // ask for SCHED_FIFO
  int fifo_priority = 80;                 // 1..99 when SCHED_FIFO is granted
  double spin_us = 100.0;                 // spin this long before each deadline (at most half a period)
  std::size_t statistics_window = 32768;  // ticks behind the percentiles
};

class HapticLoop {
 public:
  // Borrows device, scene and bvh (they must outlive the loop). `clock`: nullptr for the monotonic
  // clock; a fake clock makes the schedule and statistics deterministic (with run_ticks).
  // Throws palpate::Error for a rate out of range or an invalid transform.
  HapticLoop(Device& device, const Scene& scene, const Bvh& bvh, const HapticLoopParams& params = {},
             LoopClock* clock = nullptr);
  ~HapticLoop();
  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  // Starts the thread; the schedule and the device's time start over at 0, tick numbers and
  // statistics go on. Throws palpate::Error when already running.
  void start();
  // Stops and joins the thread (within about a period); does nothing when not running.
  void stop() noexcept;
  bool running() const noexcept { return thread_.joinable(); }
  // Whether SCHED_FIFO was granted at the last start().
  bool realtime() const noexcept { return realtime_.load(std::memory_order_relaxed); }

  // Runs `count` ticks on the calling thread as a run of its own (device time from 0, a fresh
  // schedule), with the same code and statistics as the thread: for fake clocks and tools.
  // Throws palpate::Error while the thread runs.
  void run_ticks(std::uint64_t count);

  // Any thread, never blocks the loop.
  Contact latest_contact() const noexcept { return contacts_.load(); }
  const Latest<Contact>& contacts() const noexcept { return contacts_; }
  LoopStatistics statistics() const { return stats_.snapshot(); }
  double rate_hz() const noexcept { return rate_hz_; }
  // Seconds on the loop's clock since the current run started, the scale of Contact::time_s: a reader
  // learns how old a contact is as run_time_s() - contact.time_s. Any thread with the monotonic clock.
  double run_time_s() const noexcept;

 private:
  void begin_run() noexcept;
  void run_period() noexcept;
  void thread_main() noexcept;

  HapticPipeline pipeline_;
  double rate_hz_;
  std::int64_t period_ns_;
  HapticLoopParams params_;
  std::unique_ptr<MonotonicClock> own_clock_;
  LoopClock& clock_;
  LoopStatsRecorder stats_;
  Latest<Contact> contacts_;

  std::atomic<std::int64_t> origin_ns_{0};  // device time 0 of this run
  std::int64_t period_start_ns_ = 0;        // grid point the next tick waits for
  bool first_of_run_ = true;
  std::uint64_t next_tick_ = 0;

  std::thread thread_;
  std::atomic<bool> stop_requested_{false};
  std::atomic<bool> realtime_{false};
};

}  // namespace palpate
