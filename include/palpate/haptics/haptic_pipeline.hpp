#pragma once
// One haptic tick, without the thread: device read -> device-to-scene transform -> proxy step on the
// BVH -> spring-damper with the touched object's material, clamped to the device's maximum force ->
// device write. HapticLoop calls it at its rate; benchmarks and simulations call it as fast as they
// like with their own clock.
//
// tick() never allocates, locks, logs or does I/O (beyond what the Device does), and never throws.
// Non-finite device input commands zero force, keeps the proxy where it was and sets invalid_input.
#include <cstdint>
#include <glm/vec3.hpp>

#include "palpate/core/bvh.hpp"
#include "palpate/core/contact.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/device.hpp"
#include "palpate/haptics/device_transform.hpp"
#include "palpate/haptics/proxy.hpp"

namespace palpate {

struct TickResult {
  Contact contact;             // with tick and time filled in; object -1 when free or invalid
  glm::vec3 force_n{0.0f};     // commanded force in the scene frame
  bool clamped = false;        // the force hit the device's maximum
  bool invalid_input = false;  // the device gave a non-finite position or velocity
};

class HapticPipeline {
 public:
  // Borrows all three; they must outlive the pipeline and `bvh` must be built from `scene`.
  // Reads device.limits() once. Throws palpate::Error for an invalid transform.
  HapticPipeline(Device& device, const Scene& scene, const Bvh& bvh,
                 const DeviceTransform& device_to_scene = {}, const ProxyParams& proxy = {});

  TickResult tick(std::uint64_t tick, double time_s) noexcept;

  // Puts the proxy at `scene_position_mm` (free space) and forgets its contact, e.g. between runs.
  void reset_proxy(glm::vec3 scene_position_mm) noexcept { proxy_state_.reset(scene_position_mm); }

  const DeviceLimits& limits() const noexcept { return limits_; }
  const DeviceTransform& device_to_scene() const noexcept { return device_to_scene_; }

 private:
  Device& device_;
  const Scene& scene_;
  const Bvh& bvh_;
  DeviceTransform device_to_scene_;
  ProxyParams proxy_params_;
  ProxyState proxy_state_;
  DeviceLimits limits_;
};

}  // namespace palpate
