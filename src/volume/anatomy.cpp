#include "palpate/volume/anatomy.hpp"

#include <cstdlib>
#include <functional>

#include "palpate/core/error.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/material.hpp"
#include "palpate/core/scene_file.hpp"
#include "palpate/volume/volume.hpp"

namespace palpate::volume {
namespace {

// Bumped when the pipeline changes what it makes from the same inputs.
constexpr int pipeline_version = 1;

struct ObjectRecipe {
  std::string name;
  std::filesystem::path scan;
  std::optional<float> iso;
  bool closed;
  std::size_t vertices;
  float smooth_voxels;
  Material material;
};

std::string cache_key(const ObjectRecipe& recipe, float iso) {
  std::error_code error;
  const auto canonical = std::filesystem::weakly_canonical(recipe.scan, error);
  const auto size = std::filesystem::file_size(recipe.scan, error);
  const auto time = std::filesystem::last_write_time(recipe.scan, error).time_since_epoch().count();
  const std::string inputs = canonical.string() + '|' + std::to_string(size) + '|' + std::to_string(time) +
                             '|' + std::to_string(iso) + '|' + std::to_string(recipe.smooth_voxels) + '|' +
                             std::to_string(recipe.closed) + '|' + std::to_string(recipe.vertices) + '|' +
                             std::to_string(pipeline_version);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016zx", std::hash<std::string>{}(inputs));
  return hex;
}

SceneObject build(const ObjectRecipe& recipe, const AnatomyParams& params, AnatomyObjectReport& report) {
  report.name = recipe.name;
  report.scan = recipe.scan;
  SceneObject object;
  object.name = recipe.name;
  object.material = recipe.material;

  // A cached mesh depends on the threshold, which from the histogram needs the volume: reading it is
  // skipped only when the threshold is given.
  std::optional<Volume> volume;
  float iso = 0.0f;
  if (recipe.iso) {
    iso = *recipe.iso;
  } else {
    volume = load_volume(recipe.scan);
    iso = recipe.closed ? air_threshold(*volume) : otsu_threshold(*volume);
    report.iso_from_histogram = true;
  }
  report.iso = iso;
  const std::filesystem::path cached =
      params.cache_dir.empty() ? std::filesystem::path()
                               : params.cache_dir / (recipe.name + "-" + cache_key(recipe, iso) + ".ply");
  std::error_code error;
  if (!cached.empty() && std::filesystem::exists(cached, error)) {
    try {
      object.mesh = load_mesh(cached);
      object.source = cached;
      report.from_cache = true;
      report.cached_mesh = cached;
      return object;
    } catch (const Error&) {  // a damaged cache entry is rebuilt
    }
  }
  if (!volume) volume = load_volume(recipe.scan);
  IsosurfaceParams isosurface;
  isosurface.iso = iso;
  isosurface.smooth_voxels = recipe.smooth_voxels;
  isosurface.largest = true;
  isosurface.closed = recipe.closed;
  isosurface.vertices = recipe.vertices;
  if (params.on_progress) {
    isosurface.on_progress = [&](std::string_view stage, double fraction) {
      params.on_progress(recipe.name, stage, fraction);
    };
  }
  Isosurface surface = extract_isosurface(*volume, isosurface);
  report.stages = std::move(surface.stages);
  object.mesh = std::move(surface.mesh);
  object.source = recipe.scan;
  if (!cached.empty()) {
    std::filesystem::create_directories(params.cache_dir, error);
    // Written under a temporary name and renamed, so that a reader never sees half a file.
    std::filesystem::path partial = cached;
    partial.replace_extension(".partial.ply");  // save_mesh writes by extension
    try {
      save_mesh(object.mesh, partial);
      std::filesystem::rename(partial, cached, error);
      if (!error) report.cached_mesh = cached;
    } catch (const Error&) {  // an unwritable cache costs only the next start's time
    }
  }
  return object;
}

}  // namespace

Anatomy anatomy_from_scans(const AnatomyParams& params) {
  std::vector<ObjectRecipe> recipes;
  if (!params.brain_scan.empty()) {
    recipes.push_back({"brain", params.brain_scan, params.brain_iso, false, params.brain_vertices,
                       params.brain_smooth_voxels, brain_material});
  }
  recipes.push_back({"skin", params.head_scan, params.skin_iso, true, params.skin_vertices,
                     params.skin_smooth_voxels, skin_material});
  Anatomy anatomy;
  for (const ObjectRecipe& recipe : recipes) {
    anatomy.reports.emplace_back();
    anatomy.scene.objects.push_back(build(recipe, params, anatomy.reports.back()));
  }
  return anatomy;
}

std::optional<Colin27> find_colin27(const std::filesystem::path& folder) {
  Colin27 colin{folder / "ch2.nii.gz", folder / "ch2bet.nii.gz"};
  std::error_code error;
  if (!std::filesystem::exists(colin.head, error) || !std::filesystem::exists(colin.brain, error)) return {};
  return colin;
}

std::filesystem::path default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "palpate";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache/palpate";
  return std::filesystem::temp_directory_path() / "palpate-cache";
}

Scene default_scene(const DefaultSceneParams& params) {
  const std::optional<Colin27> colin = find_colin27(params.colin27_folder);
  if (!colin) {
    if (params.on_note) {
      params.on_note("Colin27 not found (" + (params.colin27_folder / "ch2.nii.gz").string() +
                     ": install the Debian package mricron-data); using the generated phantoms");
    }
    return phantom_scene();
  }
  AnatomyParams anatomy;
  anatomy.head_scan = colin->head;
  anatomy.brain_scan = colin->brain;
  anatomy.skin_iso = Colin27::skin_iso;
  anatomy.brain_iso = Colin27::brain_iso;
  anatomy.cache_dir = params.cache_dir;
  anatomy.on_progress = params.on_progress;
  return anatomy_from_scans(anatomy).scene;
}

}  // namespace palpate::volume
