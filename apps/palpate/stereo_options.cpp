#include "stereo_options.hpp"

namespace palpate::cli {

void add_stereo_options(CLI::App* command, StereoChoice& choice) {
  command
      ->add_option("--stereo", choice.mode,
                   "Stereo output: side-by-side and top-bottom (3D TVs, head-mounted viewers), anaglyph "
                   "(red-cyan glasses), quad-buffer (shutter glasses, where the driver has a stereo visual)")
      ->check(CLI::IsMember({"off", "side-by-side", "top-bottom", "anaglyph", "quad-buffer"}))
      ->capture_default_str();
  command
      ->add_option("--mirror", choice.mirror,
                   "Flip the picture for a display seen in a half-silvered mirror (horizontal: left and "
                   "right swap)")
      ->check(CLI::IsMember({"none", "horizontal", "vertical"}))
      ->capture_default_str();
  command->add_option("--eye-separation", choice.eye_separation_mm, "Between the eyes, mm")
      ->check(CLI::Range(0.0, 200.0))
      ->capture_default_str();
  command
      ->add_option(
          "--convergence", choice.convergence_mm,
          "Distance of zero parallax (the screen), mm; default: the distance to what the camera looks at")
      ->check(CLI::PositiveNumber);
}

gl::StereoMode stereo_mode(const StereoChoice& choice) {
  if (choice.mode == "side-by-side") return gl::StereoMode::side_by_side;
  if (choice.mode == "top-bottom") return gl::StereoMode::top_bottom;
  if (choice.mode == "anaglyph") return gl::StereoMode::anaglyph;
  if (choice.mode == "quad-buffer") return gl::StereoMode::quad_buffer;
  return gl::StereoMode::mono;
}

gl::Mirror mirror(const StereoChoice& choice) {
  if (choice.mirror == "horizontal") return gl::Mirror::horizontal;
  if (choice.mirror == "vertical") return gl::Mirror::vertical;
  return gl::Mirror::none;
}

bool composited(const StereoChoice& choice) {
  return stereo_mode(choice) != gl::StereoMode::mono || mirror(choice) != gl::Mirror::none;
}

StereoCamera stereo_camera(const StereoChoice& choice, const OrbitCamera& camera) {
  StereoCamera stereo;
  stereo.eye_separation_mm = choice.eye_separation_mm;
  stereo.convergence_mm = choice.convergence_mm > 0.0f ? choice.convergence_mm : camera.distance_mm;
  return stereo;
}

}  // namespace palpate::cli
