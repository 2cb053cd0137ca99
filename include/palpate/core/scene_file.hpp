#pragma once
// Scene files (TOML) and the generated phantom scene.
//
//   # scene.toml: units are millimetres, newtons, seconds
//   [[object]]
//   name = "brain"
//   mesh = "brain.ply"               # relative to this file, or phantom:brain / phantom:skin
//   translate = [0.0, 0.0, 0.0]      # mm
//   rotate_deg = [0.0, 0.0, 0.0]     # about x, then y, then z
//   sigma_mm = 6.0
//   stiffness_n_per_mm = 0.4
//   damping_ns_per_m = 1.0
//   color = [0.9, 0.7, 0.7]
//   touchable = true
//   visible = true
//   falloff = "geodesic"             # how a dent spreads: "euclidean" (the paper), or along the surface
//
// Unknown keys, wrong types, and out-of-range values are palpate::Error naming the file and line.
#include <filesystem>

#include "palpate/core/scene.hpp"

namespace palpate {

Scene load_scene(const std::filesystem::path& file);

// Writes `scene` as a scene file and each object's mesh beside it as `<file stem>_<object name>.ply`
// (object frame; the transform as translate and rotate_deg), so that load_scene reads it back. Throws
// palpate::Error for a write error or a transform that is not a rotation and translation.
void save_scene(const Scene& scene, const std::filesystem::path& file);

// The paper's scene, generated: phantom brain inside phantom skin (brain_material, skin_material).
Scene phantom_scene();

}  // namespace palpate
