#include "palpate/haptics/haptic_pipeline.hpp"

#include "palpate/core/finite.hpp"
#include "palpate/haptics/force.hpp"

namespace palpate {

HapticPipeline::HapticPipeline(Device& device, const Scene& scene, const Bvh& bvh,
                               const DeviceTransform& device_to_scene, const ProxyParams& proxy)
    : device_(device),
      bvh_(bvh),
      materials_(scene.objects.size()),
      touchable_(scene.objects.size()),
      device_to_scene_(device_to_scene),
      proxy_params_(proxy),
      limits_(device.limits()) {
  validate_device_transform(device_to_scene_);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) set_material(i, scene.objects[i].material);
}

void HapticPipeline::set_material(std::size_t object, const Material& material) noexcept {
  if (object >= materials_.size()) return;
  materials_[object] = material;
  touchable_[object] = material.touchable;
}

TickResult HapticPipeline::tick(std::uint64_t tick, double time_s) noexcept {
  TickResult result;
  result.contact.tick = tick;
  result.contact.time_s = time_s;
  const DeviceState state = device_.read(time_s);
  if (!is_finite(state.position_mm) || !is_finite(state.velocity_mm_per_s)) {
    device_.write(glm::vec3(0.0f));
    result.invalid_input = true;
    return result;
  }
  const glm::vec3 hip = device_to_scene_.point_to_scene(state.position_mm);
  const glm::vec3 hip_velocity = device_to_scene_.velocity_to_scene(state.velocity_mm_per_s);
  result.contact = proxy_step(proxy_state_, bvh_, hip, proxy_params_, touchable_);
  result.contact.tick = tick;
  result.contact.time_s = time_s;
  const auto object = static_cast<std::size_t>(result.contact.object);
  if (result.contact.in_contact() && object < materials_.size()) {
    const ForceResult force =
        spring_damper(result.contact, hip_velocity, materials_[object], limits_.max_force_n);
    result.force_n = force.force_n;
    result.clamped = force.clamped;
    result.invalid_input = force.invalid_input;
  }
  device_.write(device_to_scene_.force_to_device(result.force_n));
  return result;
}

}  // namespace palpate
