#include "palpate/haptics/haptic_loop.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/haptics/host_steal.hpp"

namespace palpate {
namespace {

double checked_rate(double rate_hz) {
  if (!(std::isfinite(rate_hz) && rate_hz >= 1.0 && rate_hz <= 100'000.0)) {
    throw Error("haptic loop: rate must be in [1, 100000] Hz, got " + std::to_string(rate_hz));
  }
  return rate_hz;
}

// The part of the haptic thread's stack that is locked and touched before the first tick: far more
// than a tick uses (the BVH queries' stacks are under 2 KB).
constexpr std::size_t locked_stack_bytes = 64 * 1024;

// Locks and touches the stack below the caller's frame; false when the limit refuses.
[[gnu::noinline]] bool lock_stack() noexcept {
  volatile unsigned char stack[locked_stack_bytes];
  for (std::size_t i = 0; i < locked_stack_bytes; i += 4096) stack[i] = 0;
  return mlock(const_cast<unsigned char*>(stack), locked_stack_bytes) == 0;
}

}  // namespace

HapticLoop::HapticLoop(Device& device, const Scene& scene, const Bvh& bvh, const HapticLoopParams& params,
                       LoopClock* clock)
    : bvh_(bvh),
      pipeline_(device, scene, bvh, params.device_to_scene, params.proxy),
      rate_hz_(checked_rate(params.rate_hz)),
      period_ns_(std::llround(1e9 / rate_hz_)),
      params_(params),
      own_clock_(clock ? nullptr
                       : std::make_unique<MonotonicClock>(std::min<std::int64_t>(
                             std::llround(std::max(params.spin_us, 0.0) * 1e3), period_ns_ / 2))),
      clock_(clock ? *clock : *own_clock_),
      stats_(rate_hz_, params.statistics_window),
      object_count_(scene.objects.size()),
      materials_(std::make_unique<Latest<Material>[]>(scene.objects.size())),
      device_to_scene_(params.device_to_scene) {
  for (std::size_t i = 0; i < object_count_; ++i) materials_[i].store(scene.objects[i].material);
}

HapticLoop::~HapticLoop() {
  stop();
}

void HapticLoop::begin_run() noexcept {
  const std::int64_t origin = clock_.now_ns();
  origin_ns_.store(origin, std::memory_order_relaxed);
  period_start_ns_ = origin + period_ns_;
  first_of_run_ = true;
}

void HapticLoop::set_material(std::size_t object, const Material& material) {
  if (object >= object_count_) {
    throw Error("haptic loop: set_material: object " + std::to_string(object) +
                " out of range (the scene has " + std::to_string(object_count_) + ")");
  }
  if (material.touchable && !bvh_.contains(int(object))) {
    throw Error("haptic loop: set_material: object " + std::to_string(object) +
                " cannot become touchable: the BVH does not hold it (build it with Bvh::build(scene, {}))");
  }
  const std::lock_guard<std::mutex> lock(setters_);
  materials_[object].store(material);
  materials_generation_.fetch_add(1, std::memory_order_release);
}

void HapticLoop::set_device_transform(const DeviceTransform& device_to_scene) {
  validate_device_transform(device_to_scene);
  const std::lock_guard<std::mutex> lock(setters_);
  device_to_scene_.store(device_to_scene);
}

// A store that overlaps these reads shows as a newer generation or version at the next tick.
void HapticLoop::apply_live_changes() noexcept {
  const std::uint64_t generation = materials_generation_.load(std::memory_order_acquire);
  if (generation != materials_applied_) {
    materials_applied_ = generation;
    for (std::size_t i = 0; i < object_count_; ++i) pipeline_.set_material(i, materials_[i].load());
  }
  const std::uint64_t version = device_to_scene_.version();
  if (version != device_to_scene_applied_) {
    device_to_scene_applied_ = version;
    pipeline_.set_device_transform(device_to_scene_.load());
  }
}

void HapticLoop::run_period() noexcept {
  clock_.sleep_until_ns(period_start_ns_);
  const std::int64_t start_ns = clock_.now_ns();
  apply_live_changes();
  const TickResult result =
      pipeline_.tick(next_tick_, double(start_ns - origin_ns_.load(std::memory_order_relaxed)) * 1e-9);
  results_.store(result);
  const std::int64_t end_ns = clock_.now_ns();
  const std::int64_t period_end_ns = period_start_ns_ + period_ns_;
  const bool missed = end_ns > period_end_ns;
  stats_.record_tick(start_ns, end_ns, missed, result.invalid_input, first_of_run_);
  first_of_run_ = false;
  pipeline_.prepare_next_tick();  // in the period's slack: the force is already out
  ++next_tick_;
  // After a miss, start at once on the latest grid point passed: no burst of catch-up ticks.
  period_start_ns_ =
      missed ? period_start_ns_ + (end_ns - period_start_ns_) / period_ns_ * period_ns_ : period_end_ns;
}

void HapticLoop::thread_main() noexcept {
  prctl(PR_SET_TIMERSLACK, 1UL);          // wake from clock_nanosleep on time, not up to 50 us late
  if (params_.lock_memory) lock_stack();  // a refusal was already reported for the BVH
  while (!stop_requested_.load(std::memory_order_relaxed)) run_period();
}

void HapticLoop::start() {
  if (running()) throw Error("haptic loop: start() while already running");
  stop_requested_.store(false, std::memory_order_relaxed);
  steal_at_start_ms_.store(host_steal_ms().value_or(-1.0), std::memory_order_relaxed);
  begin_run();  // here, not on the thread: run_time_s() is valid as soon as start() returns
  if (params_.lock_memory) lock_bvh();
  thread_ = std::thread([this] { thread_main(); });
  bool granted = false;
  if (params_.realtime_priority) {
    sched_param priority{};
    priority.sched_priority = std::clamp(params_.fifo_priority, 1, 99);
    const int status = pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &priority);
    granted = status == 0;
    if (!granted && params_.on_log) {
      params_.on_log(std::string("haptic loop: SCHED_FIFO not permitted (") + std::strerror(status) +
                     "); running at normal priority");
    }
  }
  realtime_.store(granted, std::memory_order_relaxed);
}

LoopStatistics HapticLoop::statistics() const {
  LoopStatistics statistics = stats_.snapshot();
  const double at_start = steal_at_start_ms_.load(std::memory_order_relaxed);
  const std::optional<double> now = host_steal_ms();
  if (now && at_start >= 0.0) statistics.steal_ms = *now - at_start;
  return statistics;
}

double HapticLoop::run_time_s() const noexcept {
  return double(clock_.now_ns() - origin_ns_.load(std::memory_order_relaxed)) * 1e-9;
}

void HapticLoop::stop() noexcept {
  if (!running()) return;
  stop_requested_.store(true, std::memory_order_relaxed);
  thread_.join();
  if (locked_bytes_ > 0) {
    for (const std::span<const std::byte> range : bvh_.memory())
      if (!range.empty()) munlock(range.data(), range.size());
    locked_bytes_ = 0;
  }
}

// mlock also faults the pages in: the first tick after start() finds every node and triangle mapped.
void HapticLoop::lock_bvh() {
  std::size_t locked = 0;
  for (const std::span<const std::byte> range : bvh_.memory()) {
    if (range.empty()) continue;
    if (mlock(range.data(), range.size()) != 0) {
      const int error = errno;
      for (const std::span<const std::byte> done : bvh_.memory()) {
        if (done.data() == range.data()) break;
        if (!done.empty()) munlock(done.data(), done.size());
      }
      if (params_.on_log) {
        params_.on_log("haptic loop: could not lock the BVH's " + std::to_string(bvh_.memory_bytes() >> 20) +
                       " MiB in memory (" + std::strerror(error) +
                       "; see ulimit -l); a tick may wait for a page");
      }
      return;
    }
    locked += range.size();
  }
  locked_bytes_ = locked;
}

void HapticLoop::run_ticks(std::uint64_t count) {
  if (running()) throw Error("haptic loop: run_ticks() while the thread runs");
  begin_run();
  for (std::uint64_t i = 0; i < count; ++i) run_period();
}

}  // namespace palpate
