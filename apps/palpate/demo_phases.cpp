#include "demo_phases.hpp"

#include <algorithm>
#include <cctype>
#include <glm/geometric.hpp>
#include <limits>

#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/pick.hpp"

namespace palpate::cli {
namespace {

float volume(const Bounds& b) {
  const glm::vec3 s = b.size_mm();
  return s.x * s.y * s.z;
}

bool pressable(const SceneObject& object) {
  return object.material.visible && object.material.touchable && object.mesh.triangle_count() > 0;
}

// The visible, touchable object with the largest bounds (the skin of the default scene), or -1.
int outer_object(const Scene& scene) {
  int best = -1;
  for (int i = 0; i < int(scene.objects.size()); ++i) {
    if (!pressable(scene.objects[std::size_t(i)])) continue;
    if (best < 0 || volume(world_bounds(scene.objects[std::size_t(i)])) >
                        volume(world_bounds(scene.objects[std::size_t(best)]))) {
      best = i;
    }
  }
  return best;
}

// The largest pressable object other than `outer`, or -1.
int largest_inner(const Scene& scene, int outer) {
  int best = -1;
  for (int i = 0; i < int(scene.objects.size()); ++i) {
    if (i == outer || !pressable(scene.objects[std::size_t(i)])) continue;
    if (best < 0 || volume(world_bounds(scene.objects[std::size_t(i)])) >
                        volume(world_bounds(scene.objects[std::size_t(best)]))) {
      best = i;
    }
  }
  return best;
}

// Bounds of the visible objects: what the camera frames.
Bounds shown_bounds(const Scene& scene) {
  Bounds b;
  bool first = true;
  for (const SceneObject& object : scene.objects) {
    if (!object.material.visible || object.mesh.positions_mm.empty()) continue;
    const Bounds o = world_bounds(object);
    b = first ? o : Bounds{glm::min(b.min_mm, o.min_mm), glm::max(b.max_mm, o.max_mm)};
    first = false;
  }
  return b;
}

std::string capitalised(std::string name) {
  if (!name.empty()) name[0] = char(std::toupper(static_cast<unsigned char>(name[0])));
  return name;
}

// Objects whose `shown` entry is false are hidden and untouchable.
Scene with_shown(const Scene& scene, const std::vector<bool>& shown) {
  Scene out = scene;
  for (std::size_t i = 0; i < out.objects.size(); ++i) {
    if (!shown[i]) out.objects[i].material.visible = out.objects[i].material.touchable = false;
  }
  return out;
}

// "Skin + Brain" from the names of the shown objects, `outer` first.
std::string model_name(const Scene& scene, const std::vector<bool>& shown, int outer) {
  std::string name = shown[std::size_t(outer)] ? capitalised(scene.objects[std::size_t(outer)].name) : "";
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    if (int(i) == outer || !shown[i]) continue;
    name += (name.empty() ? "" : " + ") + capitalised(scene.objects[i].name);
  }
  return name;
}

// For each wanted viewport position (fractions from the top left), a pixel where the camera sees
// `object`: the position itself when it does, else the nearest of a 32 x 32 grid of pixels that does
// and is not already taken. Throws when the camera sees none of the object.
std::vector<glm::vec2> sites_on(const Scene& scene, const Bvh& bvh, int object, const OrbitCamera& camera,
                                glm::vec2 viewport_px, const std::vector<glm::vec2>& wanted) {
  // What hides the object hides it from the probe too: the ray must meet it first.
  const auto sees = [&](glm::vec2 pixel) { return pick(bvh, camera, pixel, viewport_px).object == object; };
  std::vector<glm::vec2> candidates;
  constexpr int grid = 32;
  for (int j = 0; j < grid; ++j) {
    for (int i = 0; i < grid; ++i) {
      const glm::vec2 pixel = (glm::vec2(i, j) + 0.5f) / float(grid) * viewport_px;
      if (sees(pixel)) candidates.push_back(pixel);
    }
  }
  if (candidates.empty()) {
    throw Error("the camera sees no touchable surface of '" + scene.objects[std::size_t(object)].name +
                "' for the probe to press");
  }
  std::vector<glm::vec2> sites;
  for (const glm::vec2 fraction : wanted) {
    const glm::vec2 pixel = fraction * viewport_px;
    if (sees(pixel)) {
      sites.push_back(pixel);
      continue;
    }
    float best = std::numeric_limits<float>::max();
    glm::vec2 chosen = candidates.front();
    for (const glm::vec2 c : candidates) {
      const bool taken = std::any_of(sites.begin(), sites.end(), [&](glm::vec2 s) { return s == c; });
      if (!taken && glm::distance(c, pixel) < best) best = glm::distance(c, pixel), chosen = c;
    }
    sites.push_back(chosen);
  }
  return sites;
}

// A short press: the skin's wide dent shows best deep and still.
PressSlideParams skin_press(float scale) {
  PressSlideParams spec;
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
SurfaceSlideParams brain_slide(float length_mm, float speed_mm_per_s, float scale) {
  SurfaceSlideParams spec;
  spec.start_height_mm *= scale;
  spec.depth_mm = 6.0f * scale;
  spec.depth_amplitude_mm = 1.5f * scale;
  spec.length_mm = length_mm * scale;
  spec.speed_mm_per_s = speed_mm_per_s * scale;
  return spec;
}

int require_outer(const Scene& scene) {
  const int outer = outer_object(scene);
  if (outer < 0)
    throw Error("the scene has no object that is visible and touchable: nothing for the probe to press");
  return outer;
}

}  // namespace

float scene_scale(const Scene& scene) {
  return glm::length(world_bounds(scene).size_mm()) / 400.0f;
}

OrbitCamera demo_camera(const Bounds& bounds, float closer) {
  OrbitCamera camera = frame_bounds(bounds, 0.6f, 0.35f);
  camera.distance_mm *= closer;
  return camera;
}

std::vector<Phase> demo_phases(const Scene& scene, glm::vec2 viewport_px) {
  std::vector<Phase> phases;
  const int outer = require_outer(scene);
  const float scale = scene_scale(scene);
  const Bvh bvh = Bvh::build(scene);
  std::vector<bool> shown(scene.objects.size());
  for (std::size_t i = 0; i < shown.size(); ++i) shown[i] = scene.objects[i].material.visible;

  Phase presses{
      model_name(scene, shown, outer), scene, demo_camera(shown_bounds(scene), 0.7f), {}, 1.5f * scale};
  const std::vector<glm::vec2> sites = sites_on(scene, bvh, outer, presses.camera, viewport_px,
                                                {{0.45f, 0.25f}, {0.6f, 0.4f}, {0.36f, 0.42f}});
  const std::vector<PressSlideParams> aimed =
      aim_at_view(scene, bvh, outer, presses.camera, sites, viewport_px, skin_press(scale));
  presses.script = press_script(aimed, 60.0f * scale);
  phases.push_back(std::move(presses));

  const int inner = largest_inner(scene, outer);
  if (inner >= 0) {
    shown[std::size_t(outer)] = false;
    Scene inside = with_shown(scene, shown);
    Phase slide{model_name(scene, shown, outer),
                inside,
                demo_camera(world_bounds(scene.objects[std::size_t(inner)]), 0.45f),
                {},
                1.5f * scale};
    // Along the smooth gyrus beside the fissure, then across the sulci at its end.
    SurfaceSlideParams spec = brain_slide(50.0f, 20.0f, scale);
    spec.screen_direction = {0.35f, -1.0f};
    const Bvh inside_bvh = Bvh::build(inside);
    const glm::vec2 start =
        sites_on(inside, inside_bvh, inner, slide.camera, viewport_px, {{0.6f, 0.2f}}).front();
    slide.script = surface_slide_script(inside, inside_bvh, inner, slide.camera, start, viewport_px, spec);
    phases.push_back(std::move(slide));
  }
  return phases;
}

std::vector<Phase> table1_phases(const Scene& scene, double seconds, glm::vec2 viewport_px) {
  const int outer = require_outer(scene);
  const int inner = largest_inner(scene, outer);
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
    Phase phase{
        model_name(scene, shown, outer), visible, demo_camera(shown_bounds(visible)), {}, 1.5f * scale};
    const Bvh bvh = Bvh::build(visible);
    const glm::vec2 start =
        sites_on(visible, bvh, touched, phase.camera, viewport_px, {{0.45f, 0.4f}}).front();
    // Slow enough that the probe stays in contact for the whole measured stretch.
    phase.script = surface_slide_script(visible, bvh, touched, phase.camera, start, viewport_px,
                                        brain_slide(60.0f, float(60.0 / std::max(1.0, seconds)), scale));
    phases.push_back(std::move(phase));
  }
  return phases;
}

}  // namespace palpate::cli
