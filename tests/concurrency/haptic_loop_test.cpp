// The haptic loop on its own thread: it starts and stops cleanly, its contacts advance and stay
// whole while other threads read them and its statistics, and nothing on the loop thread allocates.
#include "palpate/haptics/haptic_loop.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "allocation_counter.hpp"
#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/host_steal.hpp"
#include "palpate/haptics/scripted_device.hpp"

namespace palpate {
namespace {

using namespace std::chrono_literals;

// A 40 mm cube; the scripted tip presses into its top face (z = 20) and slides, over and over.
Scene cube_scene() {
  Scene scene;
  scene.objects.push_back({"cube", make_box(glm::vec3(40.0f)), glm::mat4(1.0f), Material{}, {}});
  return scene;
}

PressSlidePath press_on_top_face() {
  PressSlideParams spec;
  spec.surface_point_mm = {-10.0f, 0.0f, 20.0f};
  spec.normal = {0.0f, 0.0f, 1.0f};
  spec.slide_direction = {1.0f, 0.0f, 0.0f};
  spec.start_height_mm = 5.0f;
  spec.approach_speed_mm_per_s = 100.0f;
  spec.slide_length_mm = 20.0f;
  spec.slide_speed_mm_per_s = 200.0f;
  spec.retract_speed_mm_per_s = 100.0f;
  return PressSlidePath(spec);
}

// Waits up to `limit` for `done`; sanitizers slow the loop, so the limit is generous.
template <class Predicate>
bool eventually(Predicate done, std::chrono::milliseconds limit = 10s) {
  const auto until = std::chrono::steady_clock::now() + limit;
  while (!done()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

// Marks the loop thread for the allocation counter on its first read.
class CountingDevice final : public Device {
 public:
  explicit CountingDevice(PressSlidePath path) : inner_(std::move(path), true) {}
  DeviceState read(double time_s) noexcept override {
    if (!marked_) {
      test::count_allocations_on_this_thread();
      marked_ = true;
    }
    return inner_.read(time_s);
  }
  void write(glm::vec3 force_n) noexcept override { inner_.write(force_n); }

 private:
  ScriptedDevice inner_;
  bool marked_ = false;
};

// Also: the host's steal time is read from /proc/stat at start() and statistics(), never on the loop
// thread: none before the first start, then a count since the run began that the machine's own count
// bounds.
TEST(HapticLoopThreadTest, StartsStopsAndRestarts) {
  const Scene scene = cube_scene();
  const Bvh bvh = Bvh::build(scene);
  ScriptedDevice device(press_on_top_face(), true);
  HapticLoopParams params;
  params.realtime_priority = false;
  HapticLoop loop(device, scene, bvh, params);
  EXPECT_FALSE(loop.running());
  EXPECT_EQ(loop.statistics().steal_ms, -1.0) << "no run yet";
  const std::optional<double> steal_before = host_steal_ms();
  ASSERT_TRUE(steal_before.has_value()) << "/proc/stat has no steal column";
  loop.start();
  EXPECT_TRUE(loop.running());
  EXPECT_THROW(loop.start(), Error);
  EXPECT_THROW(loop.run_ticks(1), Error);
  ASSERT_TRUE(eventually([&] { return loop.statistics().ticks >= 20; }));
  loop.stop();
  EXPECT_FALSE(loop.running());
  const std::uint64_t ticks_after_stop = loop.statistics().ticks;
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(loop.statistics().ticks, ticks_after_stop) << "no tick after stop()";
  EXPECT_EQ(loop.latest().contact.tick + 1, ticks_after_stop);
  const double steal_during = loop.statistics().steal_ms;
  const std::optional<double> steal_after = host_steal_ms();
  ASSERT_TRUE(steal_after.has_value());
  EXPECT_GE(steal_during, 0.0);
  EXPECT_LE(steal_during, *steal_after - *steal_before);
  loop.stop();  // a second stop does nothing

  loop.start();
  ASSERT_TRUE(eventually([&] { return loop.statistics().ticks >= ticks_after_stop + 20; }));
  EXPECT_GT(loop.latest().contact.tick, ticks_after_stop) << "tick numbers go on after a restart";
}  // the destructor stops the running loop

// The sanitizers intercept mlock and make it a no-op (their shadow memory is too large to lock), so
// the kernel's count can only be checked without them.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool mlock_is_real = false;
#else
constexpr bool mlock_is_real = true;
#endif

// The kernel's count of this process's locked memory (VmLck in /proc/self/status), bytes.
std::size_t locked_now() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmLck:", 0) == 0) return std::stoul(line.substr(6)) * 1024;
  }
  return 0;
}

// While it runs, the loop keeps the BVH's pages locked (where the limit allows: else it says so) and
// gives them back when it stops; with lock_memory off it locks nothing.
TEST(HapticLoopThreadTest, LocksTheBvhWhileRunningOrSaysWhyNot) {
  Scene scene;
  scene.objects.push_back(
      {"sphere", make_bumpy_sphere(50.0f, 1.5f, 100000), glm::mat4(1.0f), Material{}, {}});
  const Bvh bvh = Bvh::build(scene);
  std::size_t bvh_bytes = 0;
  for (const auto range : bvh.memory()) bvh_bytes += range.size();
  ASSERT_GT(bvh_bytes, std::size_t(4) << 20);
  ScriptedDevice device(press_on_top_face(), true);
  std::vector<std::string> lines;
  HapticLoopParams params;
  params.realtime_priority = false;
  params.on_log = [&](const std::string& line) { lines.push_back(line); };
  const std::size_t before = locked_now();
  {
    HapticLoop loop(device, scene, bvh, params);
    loop.start();
    ASSERT_TRUE(eventually([&] { return loop.statistics().ticks >= 5; }));
    const std::size_t during = locked_now();
    if (loop.locked_bytes() > 0) {
      EXPECT_EQ(loop.locked_bytes(), bvh_bytes);
      if (mlock_is_real) {
        EXPECT_GE(during - before, bvh_bytes) << "VmLck did not grow by the BVH";
      }
      EXPECT_TRUE(lines.empty());
    } else {
      ASSERT_EQ(lines.size(), 1u);
      EXPECT_NE(lines[0].find("could not lock the BVH"), std::string::npos) << lines[0];
    }
    loop.stop();
    EXPECT_EQ(loop.locked_bytes(), 0u);
    EXPECT_LT(locked_now(), before + bvh_bytes) << "the BVH stayed locked after stop()";
  }
  params.lock_memory = false;
  HapticLoop unlocked(device, scene, bvh, params);
  unlocked.start();
  ASSERT_TRUE(eventually([&] { return unlocked.statistics().ticks >= 5; }));
  EXPECT_EQ(unlocked.locked_bytes(), 0u);
  EXPECT_LT(locked_now(), before + bvh_bytes);
}

TEST(HapticLoopThreadTest, ContactsAdvanceAndStayWholeWhileReadersPoll) {
  const Scene scene = cube_scene();
  const Bvh bvh = Bvh::build(scene);
  ScriptedDevice device(press_on_top_face(), true);
  HapticLoopParams params;
  params.realtime_priority = false;
  HapticLoop loop(device, scene, bvh, params);
  loop.start();

  std::atomic<bool> stop_readers{false};
  std::atomic<std::uint64_t> contacts_seen{0};
  struct ReaderResult {
    std::uint64_t reads = 0, inconsistent = 0, backwards = 0, in_contact = 0, stats_backwards = 0;
  };
  std::vector<ReaderResult> results(3);
  std::vector<std::thread> readers;
  for (std::size_t r = 0; r < results.size(); ++r) {
    readers.emplace_back([&, r] {
      ReaderResult& result = results[r];
      std::uint64_t last_tick = 0, last_stats_ticks = 0;
      while (!stop_readers.load(std::memory_order_relaxed)) {
        const Contact contact = loop.latest().contact;
        ++result.reads;
        if (contact.tick < last_tick) ++result.backwards;
        last_tick = contact.tick;
        if (contact.in_contact()) {
          ++result.in_contact;
          contacts_seen.fetch_add(1, std::memory_order_relaxed);
          // The depth is |HIP - SCP| of the same tick: a torn read would break it.
          if (std::abs(glm::length(contact.hip_mm - contact.point_mm) - contact.depth_mm) > 1e-3f)
            ++result.inconsistent;
        }
        if (r == 0) {  // one reader also polls the statistics
          const LoopStatistics stats = loop.statistics();
          if (stats.ticks < last_stats_ticks) ++result.stats_backwards;
          last_stats_ticks = stats.ticks;
        }
        std::this_thread::sleep_for(50us);
      }
    });
  }
  // The path takes about 0.5 s per cycle; let it press at least once.
  const bool pressed = eventually([&] { return contacts_seen.load() > 0 && loop.statistics().ticks > 600; });
  stop_readers = true;
  for (std::thread& reader : readers) reader.join();
  loop.stop();
  ASSERT_TRUE(pressed);
  for (const ReaderResult& result : results) {
    EXPECT_GT(result.reads, 0u);
    EXPECT_EQ(result.inconsistent, 0u);
    EXPECT_EQ(result.backwards, 0u);
    EXPECT_EQ(result.stats_backwards, 0u);
  }
  const LoopStatistics stats = loop.statistics();
  EXPECT_EQ(loop.latest().contact.tick + 1, stats.ticks);
  EXPECT_GT(stats.achieved_hz, 0.0);
  EXPECT_GT(stats.tick_us.max, 0.0);
  EXPECT_EQ(stats.invalid_input_ticks, 0u);
}

TEST(HapticLoopThreadTest, TheLoopThreadNeverAllocates) {
  const Scene scene = cube_scene();
  const Bvh bvh = Bvh::build(scene);
  CountingDevice device(press_on_top_face());
  HapticLoopParams params;
  params.realtime_priority = false;
  HapticLoop loop(device, scene, bvh, params);
  const std::uint64_t before = test::counted_allocations();
  loop.start();
  std::uint64_t contacts = 0;
  // Sample contacts until a whole press-slide cycle (about 0.5 s) has run on the loop thread.
  const bool ran = eventually([&] {
    if (loop.latest().contact.in_contact()) ++contacts;
    return loop.statistics().ticks > 700 && contacts > 10;
  });
  loop.stop();
  ASSERT_TRUE(ran);
  EXPECT_EQ(test::counted_allocations() - before, 0u) << "operator new was called on the haptic thread";
}

TEST(HapticLoopThreadTest, TheCounterSeesAnAllocationOnAMarkedThread) {
  const std::uint64_t before = test::counted_allocations();
  std::thread([] {
    test::count_allocations_on_this_thread();
    ::operator delete(::operator new(64));  // a direct call, which the compiler may not elide
  }).join();
  EXPECT_GE(test::counted_allocations() - before, 1u);
}

}  // namespace
}  // namespace palpate
