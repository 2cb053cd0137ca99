#pragma once
// The scripted visits of `demo` and `bench table1`: which objects are shown and touched, where the
// camera stands, and where the probe presses.
#include <string>
#include <vector>

#include "simulation.hpp"

namespace palpate::cli {

// The size of the scene against the default one (a head about 400 mm across its bounds' diagonal):
// the probe's distances and size are set for the default scene and scaled by this for others, so a
// model in other units gets the same times and the same look.
float scene_scale(const Scene& scene);

// The object that encloses the others (the largest bounds): the skin of the default scene.
int outer_object(const Scene& scene);

// Objects whose `shown` entry is false are hidden and untouchable.
Scene with_shown(const Scene& scene, const std::vector<bool>& shown);

// "Skin + Brain" from the object names, outer object first.
std::string model_name(const Scene& scene, const std::vector<bool>& shown);

// The camera of the demo's views of `bounds`, from the front left, above.
OrbitCamera demo_camera(const Bounds& bounds, float closer = 1.0f);

// The demo: presses at three sites of the outer object with all shown, then (when there is more
// than one object) the outer object hidden and the probe pressing and sliding across the largest
// inner one.
std::vector<Phase> demo_phases(const Scene& scene);

// bench table1: one long press-slide in contact on the outer shown object, for each of the paper's
// rows: the inner object alone, the outer alone, and both (a scene of one object gives one row).
std::vector<Phase> table1_phases(const Scene& scene, double seconds);

}  // namespace palpate::cli
