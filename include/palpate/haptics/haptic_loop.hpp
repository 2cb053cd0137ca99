#pragma once
// The haptic loop: a thread of its own that runs a HapticPipeline tick at a fixed rate on absolute
// deadlines and publishes each tick's whole result (contact, commanded force, flags) through a
// Latest<TickResult> that any thread may read without ever blocking the loop.
//
// Schedule: period k starts at a deadline on the grid origin + k / rate. The thread sleeps until the
// deadline (clock_nanosleep TIMER_ABSTIME, then a short spin), runs the tick, and records its start,
// duration and period; then, with the force out, readies the next tick in the period's slack
// (HapticPipeline::prepare_next_tick). A tick that ends after the end of its period is a missed
// deadline; the next tick then starts at once, on the latest grid point already passed, so a late tick
// never causes a burst of catch-up ticks (lost periods show in the achieved rate).
//
// Live changes: set_material() and set_device_transform() reach the haptic thread through
// latest-value channels and take effect at the next tick; the loop keeps running, nothing is
// allocated on its thread, and the force follows the new material from that tick on.
//
// SCHED_FIFO is requested when the thread starts; where it is not permitted, start() says so once
// through HapticLoopParams::on_log and the loop runs at normal priority. The BVH's pages and the
// thread's stack are locked in memory (mlock) and touched before the first tick, so that no tick waits
// for a page to be read back from swap or first mapped; where the limit on locked memory refuses,
// start() says so the same way and the loop runs unlocked. Inside the loop nothing
// allocates, locks, logs or does I/O; tests/concurrency/haptic_loop_test.cpp counts operator new calls
// on the loop thread.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "palpate/core/bvh.hpp"
#include "palpate/core/material.hpp"
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
  bool lock_memory = true;                // mlock the BVH and the thread's stack (see above)
  int fifo_priority = 80;                 // 1..99 when SCHED_FIFO is granted
  double spin_us = 100.0;                 // spin this long before each deadline (at most half a period)
  std::size_t statistics_window = 32768;  // ticks behind the percentiles
  // Receives what start() has to say (SCHED_FIFO or locking refused), on the thread that calls start().
  // Empty: discarded, never printed.
  std::function<void(const std::string&)> on_log;
};

class HapticLoop {
 public:
  // Borrows the device and the BVH (they must outlive the loop) and copies the scene's materials.
  // `clock`: nullptr for the monotonic clock; a fake clock makes the schedule and statistics
  // deterministic (with run_ticks). Allocates; throws palpate::Error for a rate out of range or an
  // invalid transform.
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
  // Bytes of the BVH locked in memory by the last start(); 0 when refused, off, or stopped.
  std::size_t locked_bytes() const noexcept { return locked_bytes_; }

  // Runs `count` ticks on the calling thread as a run of its own (device time from 0, a fresh
  // schedule), with the same code and statistics as the thread: for fake clocks and tools.
  // Throws palpate::Error while the thread runs.
  void run_ticks(std::uint64_t count);

  // The latest tick's result. Any thread, never blocks the loop, no allocation.
  TickResult latest() const noexcept { return results_.load(); }
  const Latest<TickResult>& results() const noexcept { return results_; }
  // Any thread, never blocks the loop; allocates a copy of the statistics window, and reads the host's
  // steal time (/proc/stat) on the calling thread.
  LoopStatistics statistics() const;

  // From the next tick on, object `object` feels like `material` (stiffness, damping, touchability),
  // with no restart. Any thread (callers are serialised among themselves; the haptic thread never
  // waits for them). Throws palpate::Error for an object out of range, or for making touchable an
  // object the BVH does not hold (build it with Bvh::build(scene, {}) to allow that).
  void set_material(std::size_t object, const Material& material);
  // From the next tick on. Any thread. Throws palpate::Error for an invalid transform.
  void set_device_transform(const DeviceTransform& device_to_scene);
  double rate_hz() const noexcept { return rate_hz_; }
  // Seconds on the loop's clock since the current run started, the scale of Contact::time_s: a reader
  // learns how old a contact is as run_time_s() - contact.time_s. Any thread with the monotonic clock.
  double run_time_s() const noexcept;

 private:
  void begin_run() noexcept;
  void apply_live_changes() noexcept;
  void run_period() noexcept;
  void thread_main() noexcept;

  const Bvh& bvh_;
  HapticPipeline pipeline_;
  double rate_hz_;
  std::int64_t period_ns_;
  HapticLoopParams params_;
  std::unique_ptr<MonotonicClock> own_clock_;
  LoopClock& clock_;
  LoopStatsRecorder stats_;
  Latest<TickResult> results_;

  // Live changes: written by set_material / set_device_transform under setters_, read by the loop.
  std::mutex setters_;
  std::size_t object_count_;
  std::unique_ptr<Latest<Material>[]> materials_;       // one per scene object
  std::atomic<std::uint64_t> materials_generation_{0};  // bumped after each set_material
  std::uint64_t materials_applied_ = 0;                 // loop thread: the generation it applied
  Latest<DeviceTransform> device_to_scene_;
  std::uint64_t device_to_scene_applied_ = 0;  // loop thread: the version it applied

  std::atomic<std::int64_t> origin_ns_{0};       // device time 0 of this run
  std::atomic<double> steal_at_start_ms_{-1.0};  // host_steal_ms() when this run started
  std::int64_t period_start_ns_ = 0;             // grid point the next tick waits for
  bool first_of_run_ = true;
  std::uint64_t next_tick_ = 0;

  std::thread thread_;
  std::atomic<bool> stop_requested_{false};
  void lock_bvh();
  std::size_t locked_bytes_ = 0;  // of the BVH, locked by the last start() (unlocked by stop())
  std::atomic<bool> realtime_{false};
};

}  // namespace palpate
