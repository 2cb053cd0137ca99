#include "core/slot_profile.hpp"

#include <algorithm>
#include <cmath>

namespace palpate::detail {
namespace {

// Vertex density on the curved pieces relative to the straight ones.
constexpr double bottom_density = 2.0;
constexpr double lip_density = 1.5;

}  // namespace

SlotShape::SlotShape(double bottom_radius_mm, double lip_radius_mm, double wall_angle_rad)
    : bottom_radius(bottom_radius_mm),
      lip_radius(lip_radius_mm),
      wall_angle(wall_angle_rad),
      cos_wall(std::cos(wall_angle_rad)),
      sin_wall(std::sin(wall_angle_rad)) {}

SlotProfile::SlotProfile(double depth, const SlotShape& shape, double scale)
    : depth_(depth),
      bottom_radius_(shape.bottom_radius * scale),
      lip_radius_(shape.lip_radius * scale),
      wall_angle_(shape.wall_angle),
      cos_wall_(shape.cos_wall),
      sin_wall_(shape.sin_wall) {
  // The two arcs alone rise (bottom + lip radius) (1 - cos angle): a shallower groove turns less.
  const double arcs = bottom_radius_ + lip_radius_;
  if (depth_ < arcs * (1.0 - cos_wall_)) {
    wall_angle_ = std::acos(std::max(-1.0, 1.0 - depth_ / arcs));
    cos_wall_ = std::cos(wall_angle_);
    sin_wall_ = std::sin(wall_angle_);
  }
  bottom_length_ = bottom_radius_ * wall_angle_;
  wall_length_ = sin_wall_ > 0.0 ? std::max(0.0, depth_ - arcs * (1.0 - cos_wall_)) / sin_wall_ : 0.0;
  lip_length_ = lip_radius_ * wall_angle_;
  rim_lateral_ = arcs * sin_wall_ + wall_length_ * cos_wall_;
}

double SlotProfile::depth_at(double lateral) const noexcept {
  const double x = std::abs(lateral);
  if (x >= rim_lateral_) return 0.0;
  const double bottom_end = bottom_radius_ * sin_wall_;
  const double wall_end = bottom_end + wall_length_ * cos_wall_;
  const double bottom_rise = bottom_radius_ * (1.0 - cos_wall_);
  double height;  // above the bottom
  if (x < bottom_end) {
    const double a = std::asin(std::min(1.0, x / bottom_radius_));
    height = bottom_radius_ * (1.0 - std::cos(a));
  } else if (x < wall_end) {
    height = bottom_rise + (x - bottom_end) * sin_wall_ / cos_wall_;
  } else {
    const double a = std::asin(std::clamp(sin_wall_ - (x - wall_end) / lip_radius_, 0.0, 1.0));
    height = bottom_rise + wall_length_ * sin_wall_ + lip_radius_ * (std::cos(a) - cos_wall_);
  }
  return std::max(0.0, depth_ - height);
}

SlotProfile::Place SlotProfile::place(double distance, double half_period) const noexcept {
  // Share the weighted arc length from the centre line to the next crest out evenly.
  const double bottom = bottom_density * bottom_length_, wall = wall_length_, lip = lip_density * lip_length_;
  const double flat = half_period - rim_lateral_;
  const double total = bottom + wall + lip + flat;
  double s = std::clamp(distance, 0.0, half_period) * total / half_period;
  if (s >= bottom + wall + lip) return {rim_lateral_ + (s - bottom - wall - lip), 0.0};
  double lateral, height;  // height above the bottom
  if (s < bottom) {
    const double a = wall_angle_ * s / bottom;
    lateral = bottom_radius_ * std::sin(a);
    height = bottom_radius_ * (1.0 - std::cos(a));
  } else if ((s -= bottom) < wall) {
    lateral = bottom_radius_ * sin_wall_ + s * cos_wall_;
    height = bottom_radius_ * (1.0 - cos_wall_) + s * sin_wall_;
  } else {
    // The lip turns back from the wall's slope to the flat rim.
    const double a = wall_angle_ * (1.0 - (s - wall) / lip);
    lateral = bottom_radius_ * sin_wall_ + wall_length_ * cos_wall_ + lip_radius_ * (sin_wall_ - std::sin(a));
    height = bottom_radius_ * (1.0 - cos_wall_) + wall_length_ * sin_wall_ +
             lip_radius_ * (std::cos(a) - cos_wall_);
  }
  return {lateral, std::max(0.0, depth_ - height)};
}

}  // namespace palpate::detail
