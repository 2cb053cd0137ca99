// Materials and the device transform change while the haptic loop runs: the change reaches the tick
// after the call, the loop never stops, and the force follows without ever dropping to zero. Also the
// loop's whole tick result (force, flags) as the application reads it, and its log callback.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <glm/geometric.hpp>
#include <string>
#include <thread>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/haptic_loop.hpp"

namespace palpate {
namespace {

using namespace std::chrono_literals;

// A 40 mm cube about the origin: its top face is z = 20.
Scene cube_scene() {
  Scene scene;
  scene.objects.push_back({"cube", make_box(glm::vec3(40.0f)), glm::mat4(1.0f), Material{}, {}});
  return scene;
}

// Holds the tip where the test puts it (at rest: the damper adds nothing) and records the force of
// every tick in a buffer made beforehand.
class RecordingDevice final : public Device {
 public:
  explicit RecordingDevice(glm::vec3 tip_mm) : tip_(tip_mm), forces_(200'000) {}
  void move_tip(glm::vec3 tip_mm) noexcept { tip_.store(tip_mm); }
  DeviceState read(double) noexcept override { return {tip_.load(), glm::vec3(0.0f), 0}; }
  void write(glm::vec3 force_n) noexcept override {
    const std::size_t n = count_.load(std::memory_order_relaxed);
    if (n < forces_.size()) forces_[n] = force_n;
    count_.store(n + 1, std::memory_order_release);
  }
  // Read these only with the loop stopped (or on its thread).
  std::size_t count() const noexcept {
    return std::min(count_.load(std::memory_order_acquire), forces_.size());
  }
  glm::vec3 force(std::size_t i) const noexcept { return forces_[i]; }

 private:
  Latest<glm::vec3> tip_;
  std::vector<glm::vec3> forces_;
  std::atomic<std::size_t> count_{0};
};

// Time advances only by sleeping: each run_ticks() tick is exactly one period.
class StepClock final : public LoopClock {
 public:
  std::int64_t now_ns() noexcept override { return now_; }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override { now_ = std::max(now_, deadline_ns); }

 private:
  std::int64_t now_ = 0;
};

Material with_stiffness(float k_n_per_mm) {
  Material m;
  m.stiffness_n_per_mm = k_n_per_mm;
  return m;
}

constexpr glm::vec3 outside{1.0f, 2.0f, 25.0f};
constexpr glm::vec3 pressed{1.0f, 2.0f, 17.0f};  // 3 mm under the top face
// The proxy floats the surface epsilon above the face.
const float depth_mm = 3.0f + float(ProxyParams{}.surface_epsilon_mm);

TEST(LiveParametersTest, MaterialAndTransformTakeEffectAtTheNextTick) {
  const Scene scene = cube_scene();
  const Bvh bvh = Bvh::build(scene);
  RecordingDevice device(outside);
  StepClock clock;
  HapticLoopParams params;
  params.realtime_priority = false;
  HapticLoop loop(device, scene, bvh, params, &clock);
  loop.run_ticks(1);
  device.move_tip(pressed);
  loop.run_ticks(3);
  ASSERT_TRUE(loop.latest().contact.in_contact());
  EXPECT_NEAR(loop.latest().force_n.z, 0.5f * depth_mm, 1e-4f) << "the scene's own k = 0.5 N/mm";

  loop.set_material(0, with_stiffness(0.8f));
  loop.run_ticks(1);
  EXPECT_NEAR(loop.latest().force_n.z, 0.8f * depth_mm, 1e-4f) << "the next tick uses the new k";
  EXPECT_NEAR(device.force(device.count() - 1).z, 0.8f * depth_mm, 1e-4f) << "and the device is sent it";

  DeviceTransform raised;
  raised.translation_mm = {0.0f, 0.0f, 1.0f};
  loop.set_device_transform(raised);
  loop.run_ticks(1);
  EXPECT_NEAR(loop.latest().contact.hip_mm.z, pressed.z + 1.0f, 1e-5f);
  EXPECT_NEAR(loop.latest().force_n.z, 0.8f * (depth_mm - 1.0f), 1e-4f);

  Material untouchable = with_stiffness(0.8f);
  untouchable.touchable = false;
  loop.set_material(0, untouchable);
  loop.run_ticks(1);
  EXPECT_FALSE(loop.latest().contact.in_contact()) << "the proxy lets go of an untouchable object";
  EXPECT_EQ(loop.latest().force_n, glm::vec3(0.0f));
  loop.set_material(0, with_stiffness(0.8f));
  loop.run_ticks(5);
  EXPECT_EQ(loop.latest().force_n, glm::vec3(0.0f)) << "touchable again with the tip inside: no jolt";
  device.move_tip(outside);
  loop.run_ticks(1);
  device.move_tip(pressed);
  loop.run_ticks(1);
  EXPECT_NEAR(loop.latest().force_n.z, 0.8f * (depth_mm - 1.0f), 1e-4f) << "pressed again from outside";
}

TEST(LiveParametersTest, RejectsWhatTheLoopCannotDo) {
  const Scene scene = cube_scene();
  const Bvh bvh = Bvh::build(scene);
  RecordingDevice device(outside);
  HapticLoopParams params;
  params.realtime_priority = false;
  HapticLoop loop(device, scene, bvh, params);
  EXPECT_THROW(loop.set_material(1, Material{}), Error);
  DeviceTransform flat;
  flat.scale = 0.0f;
  EXPECT_THROW(loop.set_device_transform(flat), Error);

  Scene hidden = scene;
  hidden.objects[0].material.touchable = false;
  const Bvh without = Bvh::build(hidden);  // holds no triangle of the untouchable cube
  HapticLoop other(device, hidden, without, params);
  EXPECT_THROW(other.set_material(0, Material{}), Error) << "the BVH does not hold it";
  const Bvh with_all = Bvh::build(hidden, {});
  HapticLoop allowed(device, hidden, with_all, params);
  EXPECT_NO_THROW(allowed.set_material(0, Material{}));
}

// The viewer's slider: stiffness moved again and again from another thread while the loop runs at
// 1 kHz and the tip stays pressed in.
TEST(LiveParametersTest, ASliderMovedWhileInContactNeverDropsTheForce) {
  const Scene scene = cube_scene();
  const Bvh bvh = Bvh::build(scene);
  RecordingDevice device(outside);
  HapticLoopParams params;
  params.realtime_priority = false;
  HapticLoop loop(device, scene, bvh, params);
  loop.start();
  const auto wait_for_tick = [&](std::uint64_t tick) {
    const auto until = std::chrono::steady_clock::now() + 10s;
    while (loop.latest().contact.tick < tick && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(200us);
    return loop.latest().contact.tick >= tick;
  };
  ASSERT_TRUE(wait_for_tick(5));
  device.move_tip(pressed);
  ASSERT_TRUE(wait_for_tick(loop.latest().contact.tick + 3));
  ASSERT_TRUE(loop.latest().contact.in_contact());
  const std::size_t first_in_contact = device.count();

  const std::array<float, 5> stiffness{0.2f, 0.35f, 0.5f, 0.65f, 0.8f};
  for (int move = 0; move < 60; ++move) {
    const float k = stiffness[std::size_t(move) % stiffness.size()];
    const std::uint64_t before = loop.latest().contact.tick;
    loop.set_material(0, with_stiffness(k));
    // The tick running during the call may still have the old k; the one after has the new.
    ASSERT_TRUE(wait_for_tick(before + 2));
    const TickResult now = loop.latest();
    ASSERT_TRUE(now.contact.in_contact());
    EXPECT_NEAR(now.force_n.z, k * depth_mm, 1e-4f) << "move " << move;
  }
  loop.stop();
  EXPECT_TRUE(loop.running() == false);
  std::size_t zero = 0, unexplained = 0;
  for (std::size_t i = first_in_contact; i < device.count(); ++i) {
    const float f = device.force(i).z;
    zero += f == 0.0f;
    bool explained = false;
    for (const float k : stiffness) explained |= std::abs(f - k * depth_mm) < 1e-4f;
    unexplained += !explained;
  }
  EXPECT_GT(device.count() - first_in_contact, 100u);
  EXPECT_EQ(zero, 0u) << "the force never dropped to zero";
  EXPECT_EQ(unexplained, 0u) << "every tick used one whole material";
}

TEST(LiveParametersTest, StartReportsARefusedRealtimePriorityThroughTheLogCallback) {
  const Scene scene = cube_scene();
  const Bvh bvh = Bvh::build(scene);
  RecordingDevice device(outside);
  std::vector<std::string> lines;
  HapticLoopParams params;
  params.on_log = [&](const std::string& line) { lines.push_back(line); };
  HapticLoop loop(device, scene, bvh, params);
  loop.start();
  loop.stop();
  if (loop.realtime()) {
    EXPECT_TRUE(lines.empty());
  } else {
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("SCHED_FIFO not permitted"), std::string::npos) << lines[0];
  }
}

}  // namespace
}  // namespace palpate
