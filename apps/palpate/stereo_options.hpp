#pragma once
// --stereo, --mirror, --eye-separation and --convergence, shared by `view` and `demo`.
#include <CLI/CLI.hpp>
#include <string>

#include "palpate/core/orbit_camera.hpp"
#include "palpate/core/stereo_camera.hpp"
#include "palpate/gl/stereo_compositor.hpp"

namespace palpate::cli {

struct StereoChoice {
  std::string mode = "off";  // off, side-by-side, top-bottom, anaglyph, quad-buffer
  std::string mirror = "none";
  float eye_separation_mm = 63.0f;
  float convergence_mm = 0.0f;  // 0: the camera's distance to what it looks at
};
void add_stereo_options(CLI::App* command, StereoChoice& choice);

gl::StereoMode stereo_mode(const StereoChoice& choice);
gl::Mirror mirror(const StereoChoice& choice);
// Whether frames go through a gl::StereoCompositor (any stereo mode, or a mirror).
bool composited(const StereoChoice& choice);
// The eyes for `camera`: zero parallax at its target unless --convergence says otherwise.
StereoCamera stereo_camera(const StereoChoice& choice, const OrbitCamera& camera);

}  // namespace palpate::cli
