#pragma once
// The cross-section of a narrow deep groove (a sulcus, the longitudinal fissure), and where to put the
// vertices of a smooth surface when that groove is folded into it. Private to palpate_core.
//
// Half the groove, from its centre line outward: a round bottom of radius `bottom_radius`, a straight
// wall rising at `wall_angle` from the horizontal, a round lip of radius `lip_radius`, then the flat rim.
// A groove too shallow for its two arcs at that angle gets a gentler angle and no straight wall: it fades
// to a smooth dip as its depth goes to 0. Lengths in mm, in the frame of the rim (a radial surface
// narrows the groove with depth).
namespace palpate::detail {

// A groove's cross-section apart from its depth: radii in mm, wall angle in (0, pi/2).
struct SlotShape {
  SlotShape(double bottom_radius_mm, double lip_radius_mm, double wall_angle_rad);
  double bottom_radius, lip_radius, wall_angle, cos_wall, sin_wall;
};

class SlotProfile {
 public:
  // A groove `depth` mm deep of `shape`, its radii scaled by `scale`. Needs no trigonometry unless the
  // groove is too shallow for its arcs.
  SlotProfile(double depth, const SlotShape& shape, double scale = 1.0);

  // Lateral distance from the centre line to where the lip meets the rim: half the groove's opening.
  double half_width() const noexcept { return rim_lateral_; }

  // Depth below the rim at `lateral` mm from the centre line: the profile as a height field (the wall is
  // steep but not vertical, so this is a function). 0 beyond half_width().
  double depth_at(double lateral) const noexcept;

  struct Place {
    double lateral;  // from the centre line, >= 0
    double depth;    // below the rim, >= 0
  };
  // A point at `distance` in [0, half_period] from the centre line on the surface before folding, where
  // the next crest stays at `half_period`, goes here. Points are spread along the profile's arc length,
  // twice as densely on the round bottom and a half more on the lip, so that the curved parts get
  // enough vertices. Needs half_period > half_width(); monotone in `distance`.
  Place place(double distance, double half_period) const noexcept;

 private:
  double depth_, bottom_radius_, lip_radius_, wall_angle_;
  double cos_wall_, sin_wall_;
  double bottom_length_, wall_length_, lip_length_;
  double rim_lateral_;
};

}  // namespace palpate::detail
