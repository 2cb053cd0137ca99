#pragma once
// Work on another core while the haptic tick is timed, as it lives beside a renderer: nothing
// ("idle"), a thread streaming memory through buffers larger than the caches ("memory"), or palpate's
// renderer drawing the Table I scene as fast as it can on a headless context ("render"; on llvmpipe the
// whole renderer runs on the CPU). The co-runner's thread, and on llvmpipe the rasterizer threads it
// starts, are pinned to one core where the system allows it.
#include <atomic>
#include <string>
#include <thread>

namespace palpate::cli {

enum class Load { idle, memory, render };
const char* load_name(Load load) noexcept;

class CoRunner {
 public:
  // Starts `load` pinned to CPU `core`; returns once it runs (a render co-runner has drawn a frame).
  // Throws palpate::Error when the renderer cannot start.
  CoRunner(Load load, int core);
  ~CoRunner();  // stops and joins it
  CoRunner(const CoRunner&) = delete;
  CoRunner& operator=(const CoRunner&) = delete;

  // Frames drawn or megabytes streamed so far: evidence that the load ran.
  long long work_done() const noexcept { return work_.load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> stop_{false}, started_{false};
  std::atomic<long long> work_{0};
  std::string error_;
  std::thread thread_;
};

// Pins the calling thread to CPU `core` while it lives, then gives it back its former CPUs.
class PinnedToCore {
 public:
  explicit PinnedToCore(int core) noexcept;
  ~PinnedToCore();
  PinnedToCore(const PinnedToCore&) = delete;
  PinnedToCore& operator=(const PinnedToCore&) = delete;

 private:
  bool restored_needed_ = false;
  unsigned char previous_[128] = {};  // a cpu_set_t
};

}  // namespace palpate::cli
