// The fold counter of the benchmarks (palpate::testing::count_folds) on cases worked by hand: a bump
// pushed up through the facing sheet of a fold crosses it, a triangle whose corner is moved across its
// opposite edge turns over, and the undeformed mesh has neither.
#include "palpate/testing/surface_checks.hpp"

#include <gtest/gtest.h>

#include "palpate/core/deform.hpp"
#include "palpate/testing/test_shapes.hpp"

namespace palpate {
namespace {

TEST(CountFolds, ABumpThroughTheFacingSheetCrossesItAndNothingTurnsOver) {
  const Mesh fold = testing::make_folded_sheet();
  const glm::vec3 contact(20.0f, 0.0f, 0.0f);
  EXPECT_EQ(testing::count_folds(fold, fold, contact, 16.0f).self_intersecting, 0u);
  Mesh moved;
  const Dent shallow{contact, -4.0f, 4.0f};  // a bump 4 mm high: under the sheet 6 mm above
  deform_mesh(fold, glm::mat4(1.0f), {&shallow, 1}, moved);
  EXPECT_EQ(testing::count_folds(fold, moved, contact, 16.0f).self_intersecting, 0u);
  const Dent through{contact, -8.0f, 4.0f};  // 8 mm: through it
  deform_mesh(fold, glm::mat4(1.0f), {&through, 1}, moved);
  const testing::FoldCounts counts = testing::count_folds(fold, moved, contact, 16.0f);
  EXPECT_GT(counts.self_intersecting, 20u);
  EXPECT_EQ(counts.inverted, 0u);
}

TEST(CountFolds, ACornerMovedAcrossItsOppositeEdgeTurnsItsTriangleOver) {
  const Mesh fold = testing::make_folded_sheet();
  Mesh moved = fold;
  const std::uint32_t* corner = &fold.indices[3 * 1000];
  const glm::vec3 a = fold.positions_mm[corner[0]], b = fold.positions_mm[corner[1]],
                  c = fold.positions_mm[corner[2]];
  moved.positions_mm[corner[0]] = b + c - a;  // a mirrored across the midpoint of bc
  const testing::FoldCounts counts = testing::count_folds(fold, moved, a, 5.0f);
  EXPECT_GE(counts.inverted, 1u);
  EXPECT_EQ(testing::count_folds(fold, fold, a, 5.0f).inverted, 0u);
}

}  // namespace
}  // namespace palpate
