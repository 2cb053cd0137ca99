// The sphere-slide reference scenario as a correctness test: a closed bumpy sphere of radius 50 mm
// with +/-1.5 mm bumps; 50 cycles of 4,000 one-millisecond ticks: from 20 mm above a random point,
// approach, press to 2.5 mm under the bumpy surface, slide 52 mm at 25 mm/s (1-4 mm deep), pull out.
// k = 1 N/mm, b = 2 N s/m. The counts (palpate/testing/haptic_scenarios.hpp defines them, judged by the
// bumpy sphere's own implicit surface, not the BVH) must all be zero. `palpate bench haptics` runs the
// same scenario through the same code.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "palpate/core/bvh.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/haptics/proxy.hpp"
#include "palpate/testing/haptic_scenarios.hpp"
#include "palpate/testing/test_shapes.hpp"
#include "proxy_move_tester.hpp"

namespace palpate {
namespace {

#if defined(__SANITIZE_ADDRESS__) || !defined(NDEBUG)
constexpr bool reduced = true;  // sanitizer and debug builds: fewer cycles, no million-triangle mesh
#else
constexpr bool reduced = false;
#endif

void expect_clean(const testing::ScenarioCounts& counts, std::uint64_t min_contact_ticks,
                  const std::string& what) {
  EXPECT_EQ(counts.pop_through_steps, 0u) << what;
  EXPECT_EQ(counts.inward_force_steps, 0u) << what;
  EXPECT_EQ(counts.proxy_inside_steps, 0u) << what;
  EXPECT_EQ(counts.stuck_cycles, 0u) << what;
  EXPECT_EQ(counts.capped_ticks, 0u) << what;
  EXPECT_GT(counts.contact_ticks, min_contact_ticks) << what << ": it really slid";
}

void sphere_slide(std::size_t triangles, int cycles) {
  const testing::BumpySphereOracle oracle(50.0f, 1.5f);
  Scene scene = testing::scene_of("bumpy sphere", make_bumpy_sphere(50.0f, 1.5f, triangles));
  scene.objects[0].material = Material{.stiffness_n_per_mm = 1.0f, .damping_ns_per_m = 2.0f};
  oracle.verify(scene.objects[0].mesh);
  const Bvh bvh = Bvh::build(scene);
  const auto cycles_run = testing::sphere_slide(oracle, {.cycles = cycles, .seed = 2007});
  const testing::ScenarioResult result = testing::run_scenario(scene, bvh, cycles_run, 1e3f, &oracle);
  expect_clean(*result.counts, std::uint64_t(cycles) * 2000u, std::to_string(triangles) + " triangles");
  // At most k * 4 mm plus the damper pressing in: a few newtons, never a spike.
  EXPECT_LT(result.counts->max_force_n, 6.0);
}

TEST(SphereSlide, TableOneBrainSize) {
  sphere_slide(22952, reduced ? 10 : 50);
}
TEST(SphereSlide, TableOneSkinSize) {
  sphere_slide(53021, reduced ? 5 : 50);
}
TEST(SphereSlide, MillionTriangles) {
  if (reduced) GTEST_SKIP() << "a million-triangle mesh is for optimised, unsanitized builds";
  sphere_slide(1000000, 50);
}

// The surface-following press-slides of `palpate bench haptics` on the folded phantom brain: the tip
// dips into sulci and climbs over gyri, and the proxy keeps up. These 50 cycles cross saddle vertices
// where three triangles' planes used to wedge the proxy (without stepping onto a nearer face it
// touches, the proxy sticks in one of cycles 41 to 50).
TEST(SurfacePressSlide, PhantomBrainGyriAndSulci) {
  Scene scene = testing::scene_of("brain", make_brain_phantom());
  const testing::MeshOracle oracle(scene);
  const Bvh bvh = Bvh::build(scene);
  const int cycles = reduced ? 5 : 50;
  const auto cycles_run = testing::surface_press_slides(scene, 0, oracle, {.cycles = cycles, .seed = 1});
  const testing::ScenarioResult result = testing::run_scenario(scene, bvh, cycles_run, 1e3f, &oracle);
  expect_clean(*result.counts, cycles, "phantom brain");
}

// How the proxy rests from tick `first` to tick `last` of press-slide `cycle` on the phantom brain:
// at most how far beyond where the surface comes nearest the tip (the oracle's own search of the mesh),
// in at most how many steps a tick, and how many ticks were cut short.
struct RestsAgainstTheNearest {
  double farthest_mm = 0.0;
  int most_steps = 0;
  int cut_short = 0;
};
RestsAgainstTheNearest rests_against_the_nearest(int cycle, std::size_t first, std::size_t last) {
  Scene scene = testing::scene_of("brain", make_brain_phantom());
  const testing::MeshOracle oracle(scene);
  const Bvh bvh = Bvh::build(scene);
  const auto cycles = testing::surface_press_slides(scene, 0, oracle, {.cycles = cycle + 1, .seed = 1});
  const std::span<const PathSample> samples = cycles[std::size_t(cycle)].samples();
  ProxyState state;
  state.reset(samples.front().position_mm);
  RestsAgainstTheNearest rests;
  for (std::size_t k = 0; k <= last; ++k) {
    const Contact contact = proxy_step(state, bvh, samples[k].position_mm);
    proxy_prepare(state, bvh);
    if (k < first) continue;
    EXPECT_TRUE(contact.in_contact()) << "tick " << k;
    const glm::dvec3 tip(contact.hip_mm);
    const double beyond = glm::distance(state.position_mm, tip) - oracle.nearest(tip, 10.0).distance_mm;
    rests.farthest_mm = std::max(rests.farthest_mm, beyond);
    rests.most_steps = std::max(rests.most_steps, state.last_iterations);
    rests.cut_short += state.last_cut_short;
  }
  return rests;
}

// At the floor of a sulcus of the phantom brain (cycle 92 of the press-slides), the tip presses 2.5 mm
// in at a vertex where two ridges and four valleys meet (the press starts there at tick 800). At each
// tick from 805 the proxy rests where the surface comes nearest the tip, in at most two steps. Reaching
// the vertex, the search used to go round the faces there one at a time, 10 steps a tick, and stop
// where it started.
TEST(SurfacePressSlide, AtASulcusFloorTheProxyRestsWhereTheSurfaceComesNearest) {
  if (reduced) GTEST_SKIP() << "93 press-slides on the phantom brain are for optimised, unsanitized builds";
  const RestsAgainstTheNearest rests = rests_against_the_nearest(92, 805, 900);
  // Measured: 1.55 um beyond, in the valley where the proxy floats the surface epsilon above two faces.
  EXPECT_LE(rests.farthest_mm, 1.6 * ProxyParams{}.surface_epsilon_mm);
  EXPECT_LE(rests.most_steps, 2);
}

// 3.7 mm deep in a sulcus of the phantom brain (cycle 135 of the press-slides, from tick 1454), three
// planes the proxy rests on meet 3.7 um from a vertex they share, past the end of their triangles, and
// the surface comes nearest the tip 0.5 mm away along a valley beyond a ridge. The proxy rests there,
// within two epsilons of where the surface comes nearest, in at most two steps, and no tick is cut
// short. It used to drop the planes, find the same ones again and go round until the cap, up to 13
// steps a tick, staying up to 76 um farther.
TEST(SurfacePressSlide, InAPocketAtAVertexTheProxyRestsWhereTheSurfaceComesNearest) {
  if (reduced) GTEST_SKIP() << "136 press-slides on the phantom brain are for optimised, unsanitized builds";
  const RestsAgainstTheNearest rests = rests_against_the_nearest(135, 1454, 1480);
  // Measured: 1.91 um beyond, in the valley where the proxy floats the surface epsilon above two faces.
  EXPECT_LE(rests.farthest_mm, 2.0 * ProxyParams{}.surface_epsilon_mm);
  EXPECT_LE(rests.most_steps, 2);
  EXPECT_EQ(rests.cut_short, 0);
}

// Wedged a second time in a tick at the same vertex, within micrometres of it, the search has gone
// round the faces there: a look toward the tip meets the next face round a micrometre away and takes
// it over, and two planes wedge the proxy again. It used to go on round until the loop check ended it.
// Now the faces round the vertex are taken together: the proxy rests where they come nearest the tip,
// or stays where it is when there is no free way there. On the phantom brain's press-slides: where a
// press first touches, the tip at a vertex (cycles 122 and 180, tick 800: 8 and 9 steps, cut short),
// and 7 um short of where the faces come nearest, deep in a fold (cycle 57, tick 1210).
TEST(SurfacePressSlide, WedgedTwiceAtAVertexTheProxyRestsWithoutGoingRound) {
  if (reduced) GTEST_SKIP() << "181 press-slides on the phantom brain are for optimised, unsanitized builds";
  for (const auto& [cycle, tick] : {std::pair{122, 800}, {180, 800}, {57, 1210}}) {
    const RestsAgainstTheNearest rests =
        rests_against_the_nearest(cycle, std::size_t(tick), std::size_t(tick));
    // Measured: 1.49, 1.81 and 1.01 um beyond, in 5, 5 and 4 steps.
    EXPECT_LE(rests.farthest_mm, 2.0 * ProxyParams{}.surface_epsilon_mm) << "cycle " << cycle;
    EXPECT_LE(rests.most_steps, 5) << "cycle " << cycle;
    EXPECT_EQ(rests.cut_short, 0) << "cycle " << cycle;
  }
}

// Deep in the phantom brain's sulci a search can come back to where one of its steps started: planes
// whose corner lies past the end of their triangles, found again face by face from where the proxy
// stands (3.4 mm deep in cycle 135, between the two banks of a sulcus, where no vertex's faces hold
// it). From there it would go round the same steps to the cap; it ends where the cap would have ended
// it, without taking them (checked against the search capped before it comes back, which runs each
// step: see proxy_move_tester.hpp).
TEST(SurfacePressSlide, ASearchThatComesBackEndsWhereTheCapWouldHaveEndedIt) {
  if (reduced) GTEST_SKIP() << "140 press-slides on the phantom brain are for optimised, unsanitized builds";
  Scene scene = testing::scene_of("brain", make_brain_phantom());
  const testing::MeshOracle oracle(scene);
  const Bvh bvh = Bvh::build(scene);
  const auto cycles = testing::surface_press_slides(scene, 0, oracle, {.cycles = 140, .seed = 1});
  const std::size_t first_cycle = 130;
  const ProxyParams params;
  int went_round = 0, steps_going_round = 0;
  for (std::size_t i = first_cycle; i < cycles.size(); ++i) {
    ProxyState state;
    state.reset(cycles[i].samples().front().position_mm);
    for (const PathSample& sample : cycles[i].samples()) {
      const ProxyState start = state;
      const Contact contact = proxy_step(state, bvh, sample.position_mm, params);
      if (state.last_cut_short && state.last_iterations < params.max_iterations) {
        ++went_round;
        steps_going_round += state.last_iterations;
        EXPECT_EQ(
            test::differs_from_the_capped_search(start, bvh, sample.position_mm, params, state, contact), "")
            << "cycle " << i;
        EXPECT_LE(oracle.depth_mm(glm::vec3(state.position_mm)), 0.0) << "cycle " << i;
      }
      proxy_prepare(state, bvh);
    }
  }
  // Measured: 10 ticks of cycle 135 came back (1717 to 1726), after 84 steps in all (each went round 4
  // steps).
  EXPECT_GE(went_round, 9);
  EXPECT_LE(went_round, 11);
  EXPECT_LE(steps_going_round, 90);
  // The scenario's counts take those ticks as cut short, like the capped ones, and find the proxy clean
  // all the same.
  const testing::ScenarioResult result =
      testing::run_scenario(scene, bvh, std::span(cycles).subspan(first_cycle), 1e3f, &oracle);
  EXPECT_GE(result.counts->capped_ticks, 9u);
  EXPECT_EQ(result.counts->pop_through_steps + result.counts->inward_force_steps +
                result.counts->proxy_inside_steps + result.counts->stuck_cycles,
            0u);
}

// `bench haptics` reports each tick's shorter time of two runs: the runs must pair tick for tick.
TEST(ShorterTicks, PairsTwoRunsTickForTick) {
  const testing::BumpySphereOracle oracle(50.0f, 1.5f);
  const Scene scene = testing::scene_of("bumpy sphere", make_bumpy_sphere(50.0f, 1.5f, 22952));
  const Bvh bvh = Bvh::build(scene);
  const auto cycles = testing::sphere_slide(oracle, {.cycles = 2, .seed = 2007});
  const testing::ScenarioResult first = testing::run_scenario(scene, bvh, cycles, 1e3f, &oracle);
  const testing::ScenarioResult second = testing::run_scenario(scene, bvh, cycles, 1e3f, nullptr);
  const testing::ScenarioResult shorter = testing::shorter_ticks(first, second);
  ASSERT_GT(first.contact_tick_us.size(), 2000u);
  ASSERT_EQ(shorter.contact_tick_us.size(), first.contact_tick_us.size());
  ASSERT_EQ(shorter.free_between_us.size(), first.free_between_us.size());
  for (std::size_t i = 0; i < first.contact_tick_us.size(); ++i) {
    ASSERT_EQ(shorter.contact_tick_us[i], std::min(first.contact_tick_us[i], second.contact_tick_us[i])) << i;
    ASSERT_EQ(shorter.contact_between_us[i],
              std::min(first.contact_between_us[i], second.contact_between_us[i]))
        << i;
  }
  for (std::size_t i = 0; i < first.free_tick_us.size(); ++i) {
    ASSERT_EQ(shorter.free_tick_us[i], std::min(first.free_tick_us[i], second.free_tick_us[i])) << i;
    ASSERT_EQ(shorter.free_between_us[i], std::min(first.free_between_us[i], second.free_between_us[i])) << i;
  }
  ASSERT_TRUE(shorter.counts.has_value());
  EXPECT_EQ(shorter.counts->contact_ticks, first.counts->contact_ticks);

  testing::ScenarioResult fewer = second;
  fewer.contact_tick_us.pop_back();
  try {
    (void)testing::shorter_ticks(first, fewer);
    ADD_FAILURE() << "runs of different lengths were paired";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("contact ticks"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace palpate
