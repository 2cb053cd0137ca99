// The proxy on the generated anatomy: random and adversarial moves against the brain
// phantom, the skin phantom and both together, at the paper's Table I sizes, checked tick by tick as in
// proxy_moves_test.cpp (see proxy_move_tester.hpp).
//
#include <gtest/gtest.h>

#include "palpate/core/phantom.hpp"
#include "palpate/testing/test_shapes.hpp"
#include "proxy_move_tester.hpp"

namespace palpate {
namespace {

using test::run_proxy_moves;

// Sulci and folds are concave: a wall may rightly hold the proxy while the tip slides on, so no lag
// check; release checks are brute force over every triangle, hence sampled. A tip jumping deep into the
// folds (a quarter of the moves are such jumps) takes the proxy a few ticks to follow.
TEST(ProxyMovesOnPhantoms, Brain) {
  run_proxy_moves(testing::scene_of("brain", make_brain_phantom()), 11,
                  {.ticks = 100000, .release_check_every = 256, .max_capped_fraction = 0.03});
}

TEST(ProxyMovesOnPhantoms, Skin) {
  run_proxy_moves(testing::scene_of("skin", make_skin_phantom()), 12,
                  {.ticks = 100000, .release_check_every = 256, .max_capped_fraction = 0.03});
}

TEST(ProxyMovesOnPhantoms, SkinAroundBrain) {
  Scene scene = testing::scene_of("skin", make_skin_phantom());
  scene.objects.push_back({"brain", make_brain_phantom(), glm::mat4(1.0f), {}, {}});
  run_proxy_moves(scene, 13, {.ticks = 100000, .release_check_every = 512, .max_capped_fraction = 0.03});
}

}  // namespace
}  // namespace palpate
