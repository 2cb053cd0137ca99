// Deep presses on folded surfaces (issue 14): a dent that falls off along the surface and pushes every
// vertex one way drives the surface through any wall behind or beside it that is thinner than the press
// is deep; with the walls giving way (SurfacePatch::PushedDent) far fewer triangles pass through others
// and none turn over. Counted by palpate::testing::count_folds (exact predicates).
#include <gtest/gtest.h>

#include <cstdio>

#include "palpate/core/deform.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/surface_patch.hpp"
#include "palpate/testing/surface_checks.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

// Presses of depth `depth_over_sigma` sigma at the centroids of `presses` triangles spread over the mesh,
// sigma 4 mm widened as the renderer widens it; the folds summed.
testing::FoldCounts folds_of_presses(const Mesh& mesh, bool walls_give_way, float depth_over_sigma,
                                     std::size_t presses) {
  constexpr float sigma_mm = 4.0f;
  SurfacePatch patch(mesh);
  Mesh deformed;
  testing::FoldCounts total;
  for (std::size_t i = 0; i < presses; ++i) {
    const std::uint32_t triangle = std::uint32_t((101 + i * 7919) % mesh.triangle_count());
    const glm::vec3 point =
        (mesh.positions_mm[mesh.indices[3 * triangle]] + mesh.positions_mm[mesh.indices[3 * triangle + 1]] +
         mesh.positions_mm[mesh.indices[3 * triangle + 2]]) /
        3.0f;
    Dent dent =
        dent_with_slope_limit(Dent{point, depth_over_sigma * sigma_mm, sigma_mm}, surface_dent_max_slope);
    if (walls_give_way) {
      patch.compute(triangle, point, SurfacePatch::PushedDent{dent.depth_mm, dent.sigma_mm});
    } else {
      patch.compute(triangle, point, dent_cutoff_sigmas * dent.sigma_mm);
    }
    dent.along_surface = true;
    dent.normal = patch.contact_normal();
    deform_mesh(mesh, glm::mat4(1.0f), {&dent, 1}, deformed, patch.samples());
    const testing::FoldCounts counts =
        testing::count_folds(mesh, deformed, point, dent_cutoff_sigmas * sigma_mm);
    total.self_intersecting += counts.self_intersecting;
    total.inverted += counts.inverted;
  }
  return total;
}

// Measured bounds: without the drag of a wall's neighbours (the slope limit over its edges) the phantom
// turns 11 triangles over and the SPM12 cortex 124 / 13.
void expect_fewer_folds(const char* name, const Mesh& mesh, std::size_t least_alone,
                        std::size_t most_given_way, std::size_t most_inverted) {
  const testing::FoldCounts alone = folds_of_presses(mesh, false, 2.0f, 20);
  const testing::FoldCounts given_way = folds_of_presses(mesh, true, 2.0f, 20);
  std::printf(
      "%s, 20 presses of 2 sigma: self-intersecting / inverted %zu / %zu with the distance alone, "
      "%zu / %zu with the walls giving way\n",
      name, alone.self_intersecting, alone.inverted, given_way.self_intersecting, given_way.inverted);
  EXPECT_GE(alone.self_intersecting, least_alone);
  EXPECT_LE(given_way.self_intersecting, most_given_way);
  EXPECT_LE(given_way.inverted, most_inverted);
}

TEST(DeepPress, OnThePhantomBrainTheWallsGiveWay) {
  expect_fewer_folds("phantom brain", make_brain_phantom(), 40, 2, 0);  // measured 52 -> 0 / 0
}

TEST(DeepPress, OnTheSpm12CortexTheWallsGiveWay) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  expect_fewer_folds("spm12 cortex", load_mesh(data / "surfaces/spm12_cortex_20484.surf.gii"), 300, 85,
                     1);  // 447 -> 76 / 1
}

}  // namespace
}  // namespace palpate
