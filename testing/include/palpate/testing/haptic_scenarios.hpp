#pragma once
// The reference scenarios of the haptic tick and their correctness counts, defined once for the tests,
// the microbenchmarks and `palpate bench haptics`: scripted tool-tip cycles run through the haptic
// pipeline in simulated time (1 ms a tick, as fast as the CPU goes), each tick timed, then checked
// against a SurfaceOracle that shares no code with the BVH or the proxy.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "palpate/core/bvh.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/sampled_path.hpp"
#include "palpate/testing/surface_oracle.hpp"

namespace palpate::testing {

inline constexpr double tick_s = 1e-3;
inline constexpr double pop_through_depth_mm = 0.5;
inline constexpr double inward_force_depth_mm = 0.2;
inline constexpr double stuck_lag_mm = 0.2;
inline constexpr double stuck_reach_mm = 0.01;
inline constexpr int stuck_grace_ticks = 1;

// What a scenario counts. Each count is defined here and computed only by run_scenario.
struct ScenarioCounts {
  // Ticks with the tip more than pop_through_depth_mm inside (by the oracle) and no force: the proxy
  // has lost the surface.
  std::uint64_t pop_through_steps = 0;
  // Ticks with the tip more than inward_force_depth_mm inside and a force with a component into the
  // surface (against its outward normal where the proxy rests): the spring pulls the tip deeper.
  std::uint64_t inward_force_steps = 0;
  // Ticks in contact with the proxy more than pop_through_depth_mm inside (by the oracle).
  std::uint64_t proxy_inside_steps = 0;
  // Cycles where the proxy is stuck: in contact, with its search finished, for more than
  // stuck_grace_ticks ticks in a row farther from the tip, by more than stuck_lag_mm, than the nearest
  // point of the faces it touches (those within stuck_reach_mm of it): a frictionless proxy slides on to
  // a local minimum of its distance to the tip, and one that stays away from it is caught (at an edge
  // or vertex it may settle a tick late: that is not counted); or still in contact at the cycle's last
  // tick, when the tip is back outside.
  std::uint64_t stuck_cycles = 0;
  // Ticks whose search was cut short: by the proxy's step cap, or on coming back to where it had been.
  std::uint64_t capped_ticks = 0;
  std::uint64_t contact_ticks = 0;
  double max_force_n = 0.0;
};

struct CycleShape {
  int cycles = 50;
  int ticks_per_cycle = 4000;       // 1 ms each
  float press_depth_mm = 2.5f;      // negative: hover above
  float depth_amplitude_mm = 1.5f;  // depth = press + amplitude sin(2 pi s / slide length)
  float start_height_mm = 20.0f;    // approach from, and retract to, this far outside
  float speed_mm_per_s = 25.0f;     // approach, slide and retract
  float slide_length_mm = 52.0f;
  std::uint32_t seed = 1;
};

// sphere-slide: on the bumpy sphere, from start_height above a random surface point, approach along
// the radius, press, slide along a great circle with the depth (measured along the radius, from the
// real bumpy surface) varying, pull out, rest; one random point and direction per cycle. Each cycle is
// the tip every millisecond, world mm.
std::vector<SampledPath> sphere_slide(const BumpySphereOracle& oracle, const CycleShape& shape);

// Press-slides that follow the real surface of object `object` (the brain's gyri and sulci, the skin's
// face): from a random vertex, approach along the surface normal, then walk along the surface (each
// millisecond a step along the heading, back onto the surface at its nearest point, the heading carried
// along as the normal turns), the tip that deep under the walked point along the interpolated vertex
// normal, pull out, rest. The slide ends early where the folds are thinner than the press (the tip
// would come nearer another part of the surface than the one it presses, and a faithful proxy could
// not be told from a stuck one); the pull-out goes only as far as the way is clear. Cycles whose
// approach would start inside the scene or cross another part of the surface are passed over. Throws
// palpate::Error when no vertex will do.
std::vector<SampledPath> surface_press_slides(const Scene& scene, std::size_t object,
                                              const MeshOracle& oracle, const CycleShape& shape);

struct ScenarioResult {
  std::vector<double> free_tick_us;     // ticks that ended out of contact
  std::vector<double> contact_tick_us;  // ticks that ended in contact
  // The work between ticks (HapticPipeline::prepare_next_tick) after each of those ticks.
  std::vector<double> free_between_us, contact_between_us;
  std::optional<ScenarioCounts> counts;  // with an oracle
};

// Runs each cycle through a HapticPipeline on `bvh` (the proxy put at the cycle's first sample, tick k
// at k ms, the device's force limit `max_force_n`), timing every tick and the work after it, as
// HapticLoop does them; with an oracle, then counts.
ScenarioResult run_scenario(const Scene& scene, const Bvh& bvh, std::span<const SampledPath> cycles,
                            float max_force_n, const SurfaceOracle* oracle);

// Each tick's shorter time in two runs of the same scenario (and of the work after it): what the
// ticks cost where the machine interrupted neither run of them, as a tick is hit in both with a
// chance near the square of its chance in one. The counts are the first run's. Throws palpate::Error
// when the runs differ in how many ticks ended free or in contact (the proxy is deterministic, so
// they cannot unless the scenarios differ).
ScenarioResult shorter_ticks(const ScenarioResult& first, const ScenarioResult& second);

}  // namespace palpate::testing
