#include "probe_scenes.hpp"

#include <cctype>
#include <glm/geometric.hpp>

#include "palpate/core/error.hpp"

namespace palpate::cli {
namespace {

float volume(const Bounds& b) {
  const glm::vec3 s = b.size();
  return s.x * s.y * s.z;
}

// Bounds of the visible objects: what the camera frames.
Bounds shown_bounds(const Scene& scene) {
  Bounds b;
  bool first = true;
  for (const SceneObject& object : scene.objects) {
    if (!object.material.visible || object.mesh.positions.empty()) continue;
    const Bounds o = world_bounds(object);
    b = first ? o : Bounds{glm::min(b.min, o.min), glm::max(b.max, o.max)};
    first = false;
  }
  return b;
}

std::string capitalised(std::string name) {
  if (!name.empty()) name[0] = char(std::toupper(static_cast<unsigned char>(name[0])));
  return name;
}

int largest_shown_inner(const Scene& scene, int outer) {
  int best = -1;
  for (int i = 0; i < int(scene.objects.size()); ++i) {
    if (i == outer) continue;
    if (best < 0 || volume(world_bounds(scene.objects[std::size_t(i)])) >
                        volume(world_bounds(scene.objects[std::size_t(best)]))) {
      best = i;
    }
  }
  return best;
}

// A short press: the skin's wide dent shows best deep and still.
PressSlide skin_press(float scale) {
  PressSlide spec;
  spec.start_height_mm = 12.0f * scale;
  spec.approach_speed_mm_per_s = 60.0f * scale;
  spec.press_depth_mm = 8.0f * scale;
  spec.slide_length_mm = 8.0f * scale;
  spec.slide_speed_mm_per_s = 16.0f * scale;
  spec.depth_amplitude_mm = 2.0f * scale;
  spec.depth_cycles = 0.5f;
  spec.retract_speed_mm_per_s = 60.0f * scale;
  spec.rest_s = 0.1f;
  return spec;
}

// A long slide across the brain's gyri and sulci, following the surface.
SurfaceSlide brain_slide(float length_mm, float speed_mm_per_s, float scale) {
  SurfaceSlide spec;
  spec.start_height_mm *= scale;
  spec.depth_mm = 6.0f * scale;
  spec.depth_amplitude_mm = 1.5f * scale;
  spec.length_mm = length_mm * scale;
  spec.speed_mm_per_s = speed_mm_per_s * scale;
  return spec;
}

}  // namespace

float scene_scale(const Scene& scene) {
  return glm::length(world_bounds(scene).size()) / 400.0f;
}

int outer_object(const Scene& scene) {
  if (scene.objects.empty()) throw Error("scene has no objects");
  int best = 0;
  for (int i = 1; i < int(scene.objects.size()); ++i) {
    if (volume(world_bounds(scene.objects[std::size_t(i)])) >
        volume(world_bounds(scene.objects[std::size_t(best)]))) {
      best = i;
    }
  }
  return best;
}

Scene with_shown(const Scene& scene, const std::vector<bool>& shown) {
  Scene out = scene;
  for (std::size_t i = 0; i < out.objects.size(); ++i) {
    if (!shown[i]) out.objects[i].material.visible = out.objects[i].material.touchable = false;
  }
  return out;
}

std::string model_name(const Scene& scene, const std::vector<bool>& shown) {
  const int outer = outer_object(scene);
  std::string name = shown[std::size_t(outer)] ? capitalised(scene.objects[std::size_t(outer)].name) : "";
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (int(i) == outer || !shown[i]) continue;
    name += (name.empty() ? "" : " + ") + capitalised(scene.objects[i].name);
  }
  return name;
}

OrbitCamera demo_camera(const Bounds& bounds, float closer) {
  OrbitCamera camera = frame_bounds(bounds, 0.6f, 0.35f);
  camera.distance_mm *= closer;
  return camera;
}

std::vector<Phase> demo_phases(const Scene& scene) {
  std::vector<Phase> phases;
  const int outer = outer_object(scene);
  const float scale = scene_scale(scene);
  const std::vector<bool> all(scene.objects.size(), true);

  Phase presses{model_name(scene, all), scene, demo_camera(world_bounds(scene), 0.7f), {}};
  const glm::vec2 sites[] = {{0.45f, 0.25f}, {0.6f, 0.4f}, {0.36f, 0.42f}};
  presses.script =
      press_script(aim_at_view(scene, outer, presses.camera, sites, skin_press(scale)), 60.0f * scale);
  presses.probe_radius_mm = 1.5f * scale;
  phases.push_back(std::move(presses));

  const int inner = largest_shown_inner(scene, outer);
  if (inner >= 0) {
    std::vector<bool> shown = all;
    shown[std::size_t(outer)] = false;
    Scene inside = with_shown(scene, shown);
    Phase slide{model_name(scene, shown),
                inside,
                demo_camera(world_bounds(scene.objects[std::size_t(inner)]), 0.45f),
                {}};
    // Along the smooth gyrus beside the fissure, then across the sulci at its end.
    SurfaceSlide spec = brain_slide(50.0f, 20.0f, scale);
    spec.screen_direction = {0.35f, -1.0f};
    slide.script = surface_slide_script(inside, inner, slide.camera, {0.6f, 0.2f}, spec);
    slide.probe_radius_mm = 1.5f * scale;
    phases.push_back(std::move(slide));
  }
  return phases;
}

std::vector<Phase> table1_phases(const Scene& scene, double seconds) {
  const int outer = outer_object(scene);
  const int inner = largest_shown_inner(scene, outer);
  const float scale = scene_scale(scene);
  std::vector<std::vector<bool>> rows;
  if (inner >= 0) {
    std::vector<bool> inner_only(scene.objects.size(), false), outer_only(scene.objects.size(), false);
    inner_only[std::size_t(inner)] = true;
    outer_only[std::size_t(outer)] = true;
    rows = {inner_only, outer_only};
  }
  rows.push_back(std::vector<bool>(scene.objects.size(), true));

  std::vector<Phase> phases;
  for (const std::vector<bool>& shown : rows) {
    const Scene visible = with_shown(scene, shown);
    const int touched = shown[std::size_t(outer)] ? outer : inner;
    Phase phase{model_name(scene, shown), visible, demo_camera(shown_bounds(visible)), {}};
    // Slow enough that the probe stays in contact for the whole measured stretch.
    phase.script = surface_slide_script(visible, touched, phase.camera, {0.45f, 0.4f},
                                        brain_slide(60.0f, float(60.0 / std::max(1.0, seconds)), scale));
    phase.probe_radius_mm = 1.5f * scale;
    phases.push_back(std::move(phase));
  }
  return phases;
}

}  // namespace palpate::cli
