// A million random and adversarial HIP moves against closed meshes, each tick checked against
// references independent of the BVH and the proxy (see proxy_move_tester.hpp for the checks).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "palpate/core/shapes.hpp"
#include "palpate/testing/test_shapes.hpp"
#include "proxy_move_tester.hpp"

namespace palpate {
namespace {

using test::run_proxy_moves;

TEST(ProxyMoves, Cube) {
  run_proxy_moves(testing::scene_of("cube", make_box(glm::vec3(40.0f))), 1,
                  {.ticks = 150000, .slide_lag_allowance_mm = 1.0});
}

TEST(ProxyMoves, Sphere) {
  run_proxy_moves(testing::scene_of("sphere", make_sphere(30.0f, 1000)), 2,
                  {.ticks = 150000, .release_check_every = 8, .slide_lag_allowance_mm = 1.0});
}

TEST(ProxyMoves, ThinPlate) {
  // 0.2 mm thick, 80 mm wide; the tip stays within 30 mm of the centre, mostly above.
  run_proxy_moves(testing::scene_of("plate", make_box({80.0f, 80.0f, 0.2f})), 3,
                  {.ticks = 150000, .confine_xy = 30.0f, .plate_top = 0.1f, .slide_lag_allowance_mm = 1.0});
}

TEST(ProxyMoves, BumpySphereOfBrainSize) {
  // The paper's brain face count (22,952): a stand-in for the phantom until it is merged.
  run_proxy_moves(testing::scene_of("bumpy sphere", make_bumpy_sphere(50.0f, 1.5f, 22952)), 4,
                  {.ticks = 200000, .release_check_every = 64, .slide_lag_allowance_mm = 3.5});
}

TEST(ProxyMoves, HollowBoxConcaveCornersFromInside) {
  run_proxy_moves(testing::scene_of("hollow box", testing::make_hollow_box(40.0f, 20.0f)), 5,
                  {.ticks = 100000});
}

TEST(ProxyMoves, CombWithNarrowSlots) {
  // 1 mm slots 6 mm deep between 2 mm teeth: concave creases and convex edges close together.
  run_proxy_moves(testing::scene_of("comb", testing::make_comb(8, 2.0f, 1.0f, 6.0f, 4.0f, 12.0f)), 6,
                  {.ticks = 150000, .release_check_every = 2});
}

TEST(ProxyMoves, SeveralTouchingAndOverlappingObjects) {
  Scene scene;
  scene.objects.push_back({"a", make_box({20.0f, 20.0f, 20.0f}), glm::mat4(1.0f), {}, {}});
  // Overlapping the first: its faces cut through the other's, making concave creases between objects.
  scene.objects.push_back(
      {"b", make_box({10.0f, 30.0f, 10.0f}), glm::translate(glm::mat4(1.0f), {8.0f, 3.0f, 6.0f}), {}, {}});
  scene.objects.push_back(
      {"c", make_sphere(6.0f, 300), glm::translate(glm::mat4(1.0f), {-14.0f, 0.0f, 12.0f}), {}, {}});
  run_proxy_moves(scene, 7, {.ticks = 100000, .release_check_every = 4});
}

}  // namespace
}  // namespace palpate
