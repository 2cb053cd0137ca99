// palpate's fast-marching distances on the real default brain (Colin27, from Debian's mricron-data;
// skipped when it is not installed) against CGAL's exact shortest paths (palpate::testing::
// weight_errors_against_exact): a contact where the march cannot check a source when it uses it.
#include <gtest/gtest.h>

#include <cstdio>

#include "palpate/core/geodesic.hpp"
#include "palpate/testing/surface_checks.hpp"
#include "palpate/volume/anatomy.hpp"

namespace palpate::volume {
namespace {

// Across a deep sulcus (5.5 mm along the surface, 2.8 through it) the front reaches a vertex through a
// triangle whose far corner it has not reached yet, so the march cannot tell that the triangle's source
// lies too near; computed afresh once all are known, it is right. The contact is the 25th of `palpate
// bench geodesic`'s on this brain.
TEST(GeodesicOnColin27, ASourceTheMarchCouldNotCheckIsCheckedAfterwards) {
  if (!find_colin27()) GTEST_SKIP() << "mricron-data is not installed";
  const Scene scene = default_scene();  // built once into the user's cache, as the tools do
  const Mesh& brain = scene.objects.at(0).mesh;
  ASSERT_GT(brain.triangle_count(), 108168u);
  const std::uint32_t triangle = 108168;
  const glm::vec3 point(-0.574924827f, -63.5882454f, 2.14712787f);
  GeodesicField field(brain);
  field.compute(triangle, point, 16.0f);
  const testing::WeightErrors errors = testing::weight_errors_against_exact(
      brain, triangle, point, 4.0f, [&](std::uint32_t v) { return field.distance_mm(v); });
  std::printf("Colin27, triangle %u, sigma 4 mm: %zu vertices, weight error mean %.4f, max %.4f of p\n",
              triangle, errors.vertices, errors.mean, errors.max);
  // Measured: max 0.031 of p (long, elsewhere); without the second look 0.041 (5% short).
  EXPECT_GT(errors.vertices, 200u);
  EXPECT_LE(errors.max, 0.035);
}

}  // namespace
}  // namespace palpate::volume
