#pragma once
// The paper's scene from real scans: a closed skin from a head scan and a closed brain from a
// brain-extracted scan, decimated to the paper's Table I vertex counts, with the paper's materials.
// Built surfaces are cached (keyed by each scan's path, size and time and by the parameters), so a
// second start reads two PLY files instead of running the pipeline.
//
// The default: Colin27, the MNI's single-subject T1 (181 x 217 x 181, 1 mm), as Debian's mricron-data
// installs it (ch2.nii.gz, the head; ch2bet.nii.gz, its brain extracted).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "palpate/core/phantom.hpp"
#include "palpate/core/scene.hpp"
#include "palpate/volume/isosurface.hpp"

namespace palpate::volume {

struct AnatomyParams {
  std::filesystem::path head_scan;           // the skin: closed against the border, largest piece
  std::filesystem::path brain_scan;          // the brain (a brain-extracted scan); empty: skin only
  std::optional<float> skin_iso, brain_iso;  // empty: from the histogram (otsu_threshold)
  // Gaussian smoothing before extraction, in voxels: more for the skin, whose thin places (ears, nose)
  // otherwise open tunnels (Colin27's skin: genus 67 at 1 voxel, 2 at 1.5).
  float skin_smooth_voxels = 1.5f, brain_smooth_voxels = 1.0f;
  std::size_t skin_vertices = skin_phantom_vertices, brain_vertices = brain_phantom_vertices;
  std::filesystem::path cache_dir;  // where built surfaces are kept; empty: nothing is cached
  // Progress of each object's stages ("skin", "smooth", 0.4). May be empty.
  std::function<void(std::string_view object, std::string_view stage, double fraction)> on_progress;
};

struct AnatomyObjectReport {
  std::string name;  // "skin" or "brain"
  std::filesystem::path scan;
  float iso = 0.0f;
  bool iso_from_histogram = false;
  bool from_cache = false;
  std::filesystem::path cached_mesh;  // empty when not cached
  std::vector<StageSummary> stages;   // empty when read from the cache
};

struct Anatomy {
  Scene scene;  // "brain" (when given) then "skin", in the scans' millimetres
  std::vector<AnatomyObjectReport> reports;
};

// Throws palpate::Error naming the scan for anything load_volume or extract_isosurface refuse.
Anatomy anatomy_from_scans(const AnatomyParams& params);

// Colin27 as mricron-data installs it, with the thresholds that give its skin and brain.
struct Colin27 {
  std::filesystem::path head, brain;
  static constexpr float skin_iso = 20.0f, brain_iso = 55.0f;
};
// Looks in /usr/share/mricron/templates (or `folder`); empty when the package is not installed.
std::optional<Colin27> find_colin27(const std::filesystem::path& folder = "/usr/share/mricron/templates");

// $XDG_CACHE_HOME/palpate, else $HOME/.cache/palpate, else a folder under the temporary directory.
std::filesystem::path default_cache_dir();

struct DefaultSceneParams {
  std::filesystem::path colin27_folder = "/usr/share/mricron/templates";
  std::filesystem::path cache_dir = default_cache_dir();
  std::function<void(const std::string&)> on_note;  // one line when falling back to the phantoms
  std::function<void(std::string_view object, std::string_view stage, double fraction)> on_progress;
};

// The tools' default scene: Colin27's brain and skin at Table I sizes when mricron-data is installed
// (built on first use, about half a minute, then cached), else the phantoms, saying so through on_note.
Scene default_scene(const DefaultSceneParams& params = {});

}  // namespace palpate::volume
