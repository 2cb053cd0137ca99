// Deep presses on the real default brain (Colin27, from Debian's mricron-data; skipped when it is not
// installed), issue 14's target: with the walls behind the dent giving way, presses of twice sigma leave
// no triangle passing through another or turned over, where the distance alone folds the surface.
#include <gtest/gtest.h>

#include <cstdio>

#include "palpate/testing/surface_checks.hpp"
#include "palpate/volume/anatomy.hpp"

namespace palpate::volume {
namespace {

TEST(DeepPressOnColin27, PressesOfTwiceSigmaLeaveNoFold) {
  if (!find_colin27()) GTEST_SKIP() << "mricron-data is not installed";
  const Scene scene = default_scene();  // built once into the user's cache, as the tools do
  const Mesh& brain = scene.objects.at(0).mesh;
  const testing::FoldCounts alone = testing::folds_of_presses(brain, false, 2.0f, 20);
  const testing::FoldCounts given_way = testing::folds_of_presses(brain, true, 2.0f, 20);
  std::printf(
      "Colin27, 20 presses of 2 sigma: self-intersecting / inverted %zu / %zu with the distance alone, "
      "%zu / %zu with the walls giving way\n",
      alone.self_intersecting, alone.inverted, given_way.self_intersecting, given_way.inverted);
  EXPECT_GT(alone.self_intersecting, 0u) << "these presses should fold the surface without the walls";
  EXPECT_EQ(given_way.self_intersecting, 0u);
  EXPECT_EQ(given_way.inverted, 0u);
}

}  // namespace
}  // namespace palpate::volume
