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
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/contact.hpp"
#include "palpate/core/material.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/device.hpp"
#include "palpate/haptics/device_transform.hpp"
#include "palpate/haptics/proxy.hpp"

namespace palpate {

// Everything one tick knows: what the haptic side publishes to the rest of the application.
struct TickResult {
  Contact contact;             // with tick and time filled in; object -1 when free or invalid
  glm::vec3 force_n{0.0f};     // commanded force in the scene frame
  bool clamped = false;        // the force hit the device's maximum
  bool invalid_input = false;  // the device gave a non-finite position or velocity
};

class HapticPipeline {
 public:
  // Borrows the device and the BVH (they must outlive the pipeline; `bvh` must be built from `scene`)
  // and copies the materials of the scene's objects, so the scene may change or go afterwards.
  // Reads device.limits() once. Allocates; throws palpate::Error for an invalid transform.
  HapticPipeline(Device& device, const Scene& scene, const Bvh& bvh,
                 const DeviceTransform& device_to_scene = {}, const ProxyParams& proxy = {});

  TickResult tick(std::uint64_t tick, double time_s) noexcept;
  // Between ticks, once the result is out: readies the proxy for the next tick (proxy_prepare), off
  // the path from device read to force. HapticLoop calls it after each tick; a caller of tick() that
  // skips it gets the same forces, from some slower ticks.
  void prepare_next_tick() noexcept { proxy_prepare(proxy_state_, bvh_); }

  // From the next tick on, object `object` feels like `material` (stiffness, damping, touchability; an
  // object the BVH does not hold stays untouchable). No allocation; ignored for an index out of range.
  // Not synchronised: call it on the thread that ticks (HapticLoop::set_material is for other threads).
  void set_material(std::size_t object, const Material& material) noexcept;
  // From the next tick on. The caller validates it (validate_device_transform).
  void set_device_transform(const DeviceTransform& device_to_scene) noexcept {
    device_to_scene_ = device_to_scene;
  }

  // Puts the proxy at `scene_position_mm` (free space) and forgets its contact, e.g. between runs.
  void reset_proxy(glm::vec3 scene_position_mm) noexcept { proxy_state_.reset(scene_position_mm); }

  const DeviceLimits& limits() const noexcept { return limits_; }
  const DeviceTransform& device_to_scene() const noexcept { return device_to_scene_; }
  const Material& material(std::size_t object) const noexcept { return materials_[object]; }
  // The proxy after the last tick (its position, planes and the segments its search cast).
  const ProxyState& proxy_state() const noexcept { return proxy_state_; }
  std::size_t object_count() const noexcept { return materials_.size(); }

 private:
  Device& device_;
  const Bvh& bvh_;
  std::vector<Material> materials_;      // one per scene object
  std::vector<std::uint8_t> touchable_;  // the proxy's object mask, from materials_
  DeviceTransform device_to_scene_;
  ProxyParams proxy_params_;
  ProxyState proxy_state_;
  DeviceLimits limits_;
};

}  // namespace palpate
