// palpate's distances along the surface against CGAL's exact shortest paths (palpate::testing::
// weight_errors_against_exact: exact, but seconds per source): the dent's weight exp(-d^2 / 2 sigma^2)
// within its reach, as a fraction of the penetration depth. palpate's windows are exact; the fast marching
// that takes over beyond them is tested here alone too (exact_mm 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>

#include "palpate/core/geodesic.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/core/surface_patch.hpp"
#include "palpate/testing/surface_checks.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

glm::vec3 centroid(const Mesh& mesh, std::uint32_t triangle) {
  return (mesh.positions_mm[mesh.indices[3 * triangle]] + mesh.positions_mm[mesh.indices[3 * triangle + 1]] +
          mesh.positions_mm[mesh.indices[3 * triangle + 2]]) /
         3.0f;
}

// At the triangle's centroid; exact out to `exact_sigmas` (fast marching beyond).
testing::WeightErrors compare_at(const Mesh& mesh, std::uint32_t triangle, float sigma_mm,
                                 float exact_sigmas = 4.0f) {
  const glm::vec3 point = centroid(mesh, triangle);
  GeodesicField field(mesh);
  field.compute(triangle, point, 4.0f * sigma_mm, {.exact_mm = exact_sigmas * sigma_mm});
  return testing::weight_errors_against_exact(mesh, triangle, point, sigma_mm,
                                              [&](std::uint32_t v) { return field.distance_mm(v); });
}

// Exact out to the radius, over the phantom's sharp crests and its saddles (where paths bend round
// vertices whose corners' angles pass 2 pi); and as SurfacePatch computes a dent for the shaders, exact
// out to 2 sigma (or its window budget), fast marching beyond.
TEST(GeodesicAgainstExact, TheDentsWeightOnTheFoldedBrainIsTheExactOne) {
  const Mesh brain = make_brain_phantom();
  SurfacePatch patch(brain);
  double worst = 0.0, worst_patch = 0.0, mean = 0.0;
  int contacts = 0;
  for (std::uint32_t triangle = 101; triangle < brain.triangle_count(); triangle += 9973) {
    const testing::WeightErrors exact = compare_at(brain, triangle, 4.0f);
    const glm::vec3 point = centroid(brain, triangle);
    patch.compute(triangle, point, 16.0f);
    const testing::WeightErrors of_patch = testing::weight_errors_against_exact(
        brain, triangle, point, 4.0f, [&](std::uint32_t v) { return patch.samples()[v].w; });
    std::printf(
        "triangle %u: %zu vertices within 4 sigma, weight error max %.5f of p exact, %.4f in the "
        "surface patch\n",
        triangle, exact.vertices, exact.max, of_patch.max);
    worst = std::max(worst, exact.max);
    worst_patch = std::max(worst_patch, of_patch.max);
    mean += exact.mean;
    ++contacts;
  }
  mean /= contacts;
  std::printf(
      "%d contacts, sigma 4 mm: weight error mean %.6f, max %.5f of p; in the surface patch max %.4f\n",
      contacts, mean, worst, worst_patch);
  // Measured: max under 0.00001 of p (float rounding); in the surface patch 0.0087. Fast marching alone
  // reached 0.021 here (0.040 on another of the phantom's contacts); issue 14's target is 0.03.
  EXPECT_LE(mean, 1e-5);
  EXPECT_LE(worst, 1e-4);
  EXPECT_LE(worst_patch, 0.015);
}

// Fast marching alone. The contact's ring: on the fsaverage5 pial surface (3 mm edges against sigma
// 2 mm), a contact whose neighbours the front reaches from the contact triangle's corners only along edges
// and across a bend; the second look after the march puts them right. The contact is the tenth of
// `palpate bench geodesic`'s.
TEST(GeodesicAgainstExact, TheContactsRingReachedAlongEdgesIsPutRight) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const Mesh pial = load_mesh(data / "surfaces/fsaverage5_pial_left.gii.gz");
  const std::uint32_t triangle = 6164;
  const glm::vec3 point(-59.6568756f, -8.11405945f, 6.62274027f);
  GeodesicField field(pial);
  field.compute(triangle, point, 8.0f, {.exact_mm = 0.0f});
  const testing::WeightErrors errors = testing::weight_errors_against_exact(
      pial, triangle, point, 2.0f, [&](std::uint32_t v) { return field.distance_mm(v); });
  std::printf("fsaverage5, triangle %u, sigma 2 mm: %zu vertices, weight error mean %.4f, max %.4f of p\n",
              triangle, errors.vertices, errors.mean, errors.max);
  // Measured: max 0.0001 of p; 0.041 before the ring's vertices were either seeded at their straight-line
  // distances or looked at again.
  EXPECT_GT(errors.vertices, 20u);
  EXPECT_LE(errors.max, 0.01);
}

// Fast marching alone: where the second look at a vertex changes it by more than 1%, its neighbours are
// looked at again, the ones it reached before too. Two contacts where that matters (at their triangles'
// centroids).
TEST(GeodesicAgainstExact, AVertexThatChangesSendsItsNeighboursBackToBeLookedAtAgain) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const Mesh pial = load_mesh(data / "surfaces/fsaverage5_pial_left.gii.gz");
  const Mesh cortex = load_mesh(data / "surfaces/spm12_cortex_20484.surf.gii");
  const testing::WeightErrors on_pial = compare_at(pial, 17758, 4.0f, 0.0f),
                              on_cortex = compare_at(cortex, 34189, 8.0f, 0.0f);
  std::printf("fsaverage5, triangle 17758, sigma 4 mm: weight error max %.4f of p\n", on_pial.max);
  std::printf("spm12 cortex, triangle 34189, sigma 8 mm: weight error max %.4f of p\n", on_cortex.max);
  // Measured: 0.0045 and 0.0125; without looking back 0.0126 and 0.0210.
  EXPECT_LE(on_pial.max, 0.008);
  EXPECT_LE(on_cortex.max, 0.016);
}

}  // namespace
}  // namespace palpate
