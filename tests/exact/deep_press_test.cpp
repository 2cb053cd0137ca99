// Deep presses on folded surfaces (issue 14): a dent that falls off along the surface and pushes every
// vertex one way drives the surface through any wall behind or beside it that is thinner than the press
// is deep; with the walls giving way (SurfacePatch::PushedDent) none turn over, and on the phantom none
// pass through another. Counted by palpate::testing::count_folds (exact predicates). The real brain's
// presses are in tests/volume/colin27_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>

#include "palpate/core/load.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/testing/surface_checks.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

void expect_fewer_folds(const char* name, const Mesh& mesh, std::size_t least_alone,
                        std::size_t most_given_way, std::size_t most_inverted) {
  const testing::FoldCounts alone = testing::folds_of_presses(mesh, false, 2.0f, 20);
  const testing::FoldCounts given_way = testing::folds_of_presses(mesh, true, 2.0f, 20);
  std::printf(
      "%s, 20 presses of 2 sigma: self-intersecting / inverted %zu / %zu with the distance alone, "
      "%zu / %zu with the walls giving way\n",
      name, alone.self_intersecting, alone.inverted, given_way.self_intersecting, given_way.inverted);
  EXPECT_GE(alone.self_intersecting, least_alone);
  EXPECT_LE(given_way.self_intersecting, most_given_way);
  EXPECT_LE(given_way.inverted, most_inverted);
}

TEST(DeepPress, OnThePhantomBrainTheWallsGiveWay) {
  expect_fewer_folds("phantom brain", make_brain_phantom(), 40, 0, 0);  // measured 52 -> 0 / 0
}

TEST(DeepPress, OnTheSpm12CortexTheWallsGiveWay) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  // Triangles as long as sigma (4.1-4.3 mm edges where they cross): a wall's corners move as far as the
  // dent needs between them (SurfacePatch::wall_reach_edges).
  expect_fewer_folds("spm12 cortex", load_mesh(data / "surfaces/spm12_cortex_20484.surf.gii"), 300, 0,
                     0);  // 447 -> 0 / 0
}

}  // namespace
}  // namespace palpate
