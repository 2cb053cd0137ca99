#include "palpate/haptics/haptic_pipeline.hpp"

#include <cmath>

#include "palpate/haptics/force.hpp"

namespace palpate {
namespace {

bool finite(glm::vec3 v) noexcept {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

HapticPipeline::HapticPipeline(Device& device, const Scene& scene, const Bvh& bvh,
                               const DeviceTransform& device_to_scene, const ProxyParams& proxy)
    : device_(device),
      scene_(scene),
      bvh_(bvh),
      device_to_scene_(device_to_scene),
      proxy_params_(proxy),
      limits_(device.limits()) {
  validate_device_transform(device_to_scene_);
}

TickResult HapticPipeline::tick(std::uint64_t tick, double time_s) noexcept {
  TickResult result;
  result.contact.tick = tick;
  result.contact.time_s = time_s;
  const DeviceState state = device_.read(time_s);
  if (!finite(state.position_mm) || !finite(state.velocity_mm_per_s)) {
    device_.write(glm::vec3(0.0f));
    result.invalid_input = true;
    return result;
  }
  const glm::vec3 hip = device_to_scene_.point_to_scene(state.position_mm);
  const glm::vec3 hip_velocity = device_to_scene_.velocity_to_scene(state.velocity_mm_per_s);
  result.contact = proxy_step(proxy_state_, bvh_, hip, proxy_params_);
  result.contact.tick = tick;
  result.contact.time_s = time_s;
  const auto object = static_cast<std::size_t>(result.contact.object);
  if (result.contact.in_contact() && object < scene_.objects.size()) {
    const ForceResult force =
        spring_damper(result.contact, hip_velocity, scene_.objects[object].material, limits_.max_force_n);
    result.force_n = force.force_n;
    result.clamped = force.clamped;
    result.invalid_input = force.invalid_input;
  }
  device_.write(device_to_scene_.force_to_device(result.force_n));
  return result;
}

}  // namespace palpate
