#pragma once
// Path scenarios for `palpate bench haptics`: scripted tool-tip cycles run through the haptic
// pipeline in simulated time (1 ms per tick, as fast as the CPU goes), each tick timed and checked
// against a reference surface independent of the BVH and the proxy: the bumpy sphere's implicit
// surface, or any closed mesh through MeshReference.
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/mesh.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/press_slide_path.hpp"
#include "palpate/haptics/sampled_path.hpp"
#include "surface_reference.hpp"

namespace palpate::cli {

// The correctness counts of a path scenario.
struct PathChecks {
  std::uint64_t pop_through_steps = 0;   // tip > 0.5 mm inside and no force
  std::uint64_t inward_force_steps = 0;  // tip > 0.2 mm inside and the force points inward
  std::uint64_t proxy_inside_steps = 0;  // in contact with the proxy (SCP) > 0.5 mm inside
  double max_force_n = 0.0;
  std::uint64_t stuck_cycles = 0;  // cycles with a stuck step (see haptic_scenarios.cpp)
};

struct ScenarioResult {
  std::vector<double> free_tick_us;     // ticks that ended out of contact
  std::vector<double> contact_tick_us;  // ticks that ended in contact
  std::optional<PathChecks> checks;     // with a reference surface
};

// One cycle per path, the proxy reset to the path's first sample before each; tick k at k ms.
// Object 0 of `scene` gives the material; the device has `max_force_n`.
ScenarioResult run_cycles(const Scene& scene, const Bvh& bvh, const std::vector<SampledPath>& cycles,
                          float max_force_n, const SurfaceReference* reference);

struct CycleShape {
  int cycles = 50;
  int ticks_per_cycle = 4000;       // 1 ms each
  float press_depth_mm = 2.5f;      // negative: hover above
  float depth_amplitude_mm = 1.5f;  // depth varies press +/- amplitude over the slide
  std::uint32_t seed = 1;
};

// sphere-slide: from 20 mm above a random surface point, approach at 25 mm/s, press, slide 52 mm
// along a great circle at 25 mm/s with the depth (measured on the reference surface) varying, pull
// out at 25 mm/s, rest; one random point and direction per cycle.
std::vector<SampledPath> sphere_slide_cycles(const BumpySphereReference& reference, const CycleShape& shape);

// The same press-slide aimed at random vertices of object `object` (along their vertex normals),
// sliding on the sphere through the vertex about the object's bounding-box centre; one per cycle.
// With `reference`, vertices whose path would start inside the scene (in a fold, the smoothed normal
// can point into a neighbouring gyrus) are passed over: a tip that starts inside is by design followed
// without force, which the checks would count as pop-through.
std::vector<PressSlide> aimed_press_slides(const Scene& scene, std::size_t object, const CycleShape& shape,
                                           const SurfaceReference* reference = nullptr);
// Those press-slides sampled at the ticks.
std::vector<SampledPath> aimed_cycles(const Scene& scene, std::size_t object, const CycleShape& shape,
                                      const SurfaceReference* reference = nullptr);

}  // namespace palpate::cli
