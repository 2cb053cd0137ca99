#pragma once
// Random and adversarial HIP moves (fast, grazing, aimed at edges and vertices, through thin plates,
// pressing and sliding) against a scene. After every tick they are checked against references that
// share no code with the BVH or the proxy:
// - the proxy is never inside a closed mesh (ray winding count), nor on the wrong side of a plate;
// - the contact is consistent and its spring never points into the surface;
// - when the tip is outside and the straight path from the proxy to it is clear (brute-force segment
//   test), the contact is released and the proxy is at the tip;
// - while pressing and sliding, the proxy keeps up with the tip (no stuck proxy);
// - a tick's search rarely runs into the segment cap;
// - a search that came back to where one of its steps started ended where the cap would have ended it.
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>

#include "palpate/core/bvh.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/proxy.hpp"

namespace palpate::test {

struct MoveOptions {
  int ticks = 100000;           // a tenth in sanitizer and debug builds (never none)
  int release_check_every = 1;  // brute-force path checks are O(triangles): sample them on big meshes
  // For a plate centred at z = 0: the tip stays within |x|, |y| <= confine_xy, so the proxy can never go
  // round the rim, and it must stay on the side it was put (|z| > plate_top).
  float confine_xy = 0.0f;
  float plate_top = 0.0f;
  // On convex and bumpy shapes, while pressing d mm and sliding, the proxy stays within d + this of the
  // tip; a stuck proxy falls further and further behind. (Not for concave scenes, where a wall may
  // rightly hold the proxy while the tip slides on into it.)
  double slide_lag_allowance_mm = 0.0;
  // Ticks whose search may run into the segment cap: a tip jumping right across a curved or folded
  // object is followed over a few ticks.
  double max_capped_fraction = 0.01;
};

// Runs the moves with a fixed seed; failures are reported through GoogleTest (at most ten printed).
void run_proxy_moves(const Scene& scene, std::uint32_t seed, MoveOptions options);

// For a step from `start` toward `hip` that came back to where one of its steps started after n steps
// and ended there (`ended`, `contact`), before its cap: what differs from the search capped at each
// step up to n, which never sees itself come back, or "" when nothing does. Step n must start as a
// step of the loop did, and the step capped at n + k must end as the one capped at the loop's step
// that n + k falls on.
std::string differs_from_the_capped_search(const ProxyState& start, const Bvh& bvh, glm::vec3 hip,
                                           const ProxyParams& params, const ProxyState& ended,
                                           const Contact& contact);

}  // namespace palpate::test
