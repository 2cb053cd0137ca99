// palpate's fast-marching distances against CGAL's exact shortest paths (palpate::testing::
// weight_errors_against_exact: exact, but seconds per source) on the folded phantom brain: the dent's weight
// exp(-d^2 / 2 sigma^2) within its reach, as a fraction of the penetration depth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>

#include "palpate/core/geodesic.hpp"
#include "palpate/core/phantom.hpp"
#include "palpate/testing/surface_checks.hpp"

namespace palpate {
namespace {

// At the triangle's centroid, sigma 4 mm.
testing::WeightErrors compare_at(const Mesh& mesh, std::uint32_t triangle, float sigma_mm) {
  const glm::vec3 point =
      (mesh.positions_mm[mesh.indices[3 * triangle]] + mesh.positions_mm[mesh.indices[3 * triangle + 1]] +
       mesh.positions_mm[mesh.indices[3 * triangle + 2]]) /
      3.0f;
  GeodesicField field(mesh);
  field.compute(triangle, point, 4.0f * sigma_mm);
  return testing::weight_errors_against_exact(mesh, triangle, point, sigma_mm,
                                              [&](std::uint32_t v) { return field.distance_mm(v); });
}

TEST(GeodesicAgainstExact, TheDentsWeightOnTheFoldedBrainIsCloseToTheExactOne) {
  const Mesh brain = make_brain_phantom();
  double worst = 0.0, mean = 0.0;
  int contacts = 0;
  for (std::uint32_t triangle = 101; triangle < brain.triangle_count(); triangle += 9973) {
    const testing::WeightErrors errors = compare_at(brain, triangle, 4.0f);
    std::printf("triangle %u: %zu vertices within 4 sigma, weight error mean %.4f, max %.4f of p\n", triangle,
                errors.vertices, errors.mean, errors.max);
    worst = std::max(worst, errors.max);
    mean += errors.mean;
    ++contacts;
  }
  mean /= contacts;
  std::printf("%d contacts, sigma 4 mm: weight error mean %.4f, max %.4f of p\n", contacts, mean, worst);
  // Measured: mean 0.0007, max 0.048 of p (issue 14's target, 0.03, is not met here: the worst vertices
  // lie over the phantom's sharp crests; on the decimated Colin27 brain, `palpate bench geodesic`).
  EXPECT_LE(mean, 0.002);
  EXPECT_LE(worst, 0.07);
}

}  // namespace
}  // namespace palpate
