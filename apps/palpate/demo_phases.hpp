#pragma once
// The scripted visits of `demo` and `bench table1`: which objects are shown and touched, where the
// camera stands, and where the probe presses.
#include <glm/vec2.hpp>
#include <string>
#include <vector>

#include "palpate/core/orbit_camera.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/haptics/probe_script.hpp"

namespace palpate::cli {

// One stretch of a run: a scene state (which objects are visible and touchable), a camera and what
// the probe does.
struct Phase {
  std::string model;  // the row name in the paper's Table I: "Brain", "Skin", "Skin + Brain"
  Scene scene;
  OrbitCamera camera;
  ProbeScript script;
  float probe_radius_mm = 1.5f;  // the sphere drawn at the tip
};

// The size of the scene against the default one (a head about 400 mm across its bounds' diagonal):
// the probe's distances and size are set for the default scene and scaled by this for others, so a
// model in other units gets the same times and the same look.
float scene_scale(const Scene& scene);

// The camera of the demo's views of `bounds`, from the front left, above.
OrbitCamera demo_camera(const Bounds& bounds, float closer = 1.0f);

// The demo: presses at three sites of the largest visible, touchable object with all shown, then (when
// there is another) that object hidden and the probe pressing and sliding across the largest one
// inside. Sites are chosen where the camera sees the object in a viewport of `viewport_px`. Throws
// palpate::Error in one line when the scene has nothing the probe can press.
std::vector<Phase> demo_phases(const Scene& scene, glm::vec2 viewport_px);

// bench table1: one long press-slide in contact on the outer shown object, for each of the paper's
// rows: the inner object alone, the outer alone, and both (a scene of one object gives one row).
std::vector<Phase> table1_phases(const Scene& scene, double seconds, glm::vec2 viewport_px);

}  // namespace palpate::cli
