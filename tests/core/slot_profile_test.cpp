#include "core/slot_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace palpate::detail {
namespace {

constexpr double degrees = std::numbers::pi / 180.0;

TEST(SlotProfile, PlacesTheCentreAtTheBottomAndTheCrestOnTheRim) {
  const SlotProfile slot(12.0, SlotShape(1.0, 1.5, 85.0 * degrees));
  const SlotProfile::Place centre = slot.place(0.0, 8.0), crest = slot.place(8.0, 8.0);
  EXPECT_DOUBLE_EQ(centre.lateral, 0.0);
  EXPECT_NEAR(centre.depth, 12.0, 1e-12);
  EXPECT_NEAR(crest.lateral, 8.0, 1e-12);
  EXPECT_DOUBLE_EQ(crest.depth, 0.0);
  // Half the opening: two arcs and the wall's run, (1 + 1.5) sin 85 + wall cos 85.
  const double wall = (12.0 - 2.5 * (1.0 - std::cos(85.0 * degrees))) / std::sin(85.0 * degrees);
  EXPECT_NEAR(slot.half_width(), 2.5 * std::sin(85.0 * degrees) + wall * std::cos(85.0 * degrees), 1e-12);
}

TEST(SlotProfile, PlacesPointsOnTheProfileInOrderAndEvenlyAlongIt) {
  const SlotProfile slot(12.0, SlotShape(1.0, 1.5, 85.0 * degrees));
  constexpr int steps = 400;
  double last_lateral = -1.0, total = 0.0;
  SlotProfile::Place previous = slot.place(0.0, 8.0);
  std::vector<double> wall_steps;
  for (int i = 1; i <= steps; ++i) {
    const SlotProfile::Place p = slot.place(8.0 * i / steps, 8.0);
    EXPECT_GT(p.lateral, last_lateral);  // monotone: keeps lateral order, so it cannot fold
    last_lateral = p.lateral;
    EXPECT_NEAR(slot.depth_at(p.lateral), p.depth, 1e-9);  // on the profile
    const double step = std::hypot(p.lateral - previous.lateral, p.depth - previous.depth);
    total += step;
    if (p.depth > 3.0 && p.depth < 9.0) wall_steps.push_back(step);
    previous = p;
  }
  // Along the straight wall the steps are equal; the whole length is the bottom arc, the wall, the lip
  // arc and the rest of the rim (the polyline's chords fall short of the arcs by a little).
  for (double s : wall_steps) EXPECT_NEAR(s, wall_steps.front(), 1e-9);
  const double angle = 85.0 * degrees;
  const double wall = (12.0 - 2.5 * (1.0 - std::cos(angle))) / std::sin(angle);
  EXPECT_NEAR(total, 1.0 * angle + wall + 1.5 * angle + (8.0 - slot.half_width()), 0.01);
}

TEST(SlotProfile, FadesToAFlatSurfaceAsItGetsShallow) {
  const SlotProfile shallow(0.5,
                            SlotShape(1.0, 1.5, 85.0 * degrees));  // too shallow for its arcs at 85 degrees
  double steepest = 0.0;
  for (double x = 0.0; x < 3.0; x += 0.01) {
    steepest = std::max(steepest, (shallow.depth_at(x) - shallow.depth_at(x + 0.01)) / 0.01);
  }
  EXPECT_NEAR(shallow.depth_at(0.0), 0.5, 1e-12);
  EXPECT_LT(steepest, 1.2);  // a gentle dip, no wall
  const SlotProfile none(0.0, SlotShape(1.0, 1.5, 85.0 * degrees));
  EXPECT_EQ(none.half_width(), 0.0);
  EXPECT_EQ(none.place(3.0, 8.0).lateral, 3.0);
  EXPECT_EQ(none.place(3.0, 8.0).depth, 0.0);
}

}  // namespace
}  // namespace palpate::detail
