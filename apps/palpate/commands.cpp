#include "commands.hpp"

#include <cstdio>
#include <map>

#include "palpate/core/scene_file.hpp"
#include "palpate/volume/anatomy.hpp"
#include "progress.hpp"

namespace palpate::cli {
namespace {

std::map<const CLI::App*, std::function<int()>>& actions() {
  static std::map<const CLI::App*, std::function<int()>> registry;
  return registry;
}

int run_in(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) {
    if (int status = run_in(*sub); status >= 0) return status;
  }
  const auto it = actions().find(&app);
  return it == actions().end() ? -1 : it->second();
}

}  // namespace

void on_selected(CLI::App* command, std::function<int()> action) {
  actions()[command] = std::move(action);
}

void add_scene_options(CLI::App* command, SceneChoice& choice) {
  command->add_option("--scene", choice.file,
                      "Scene file (TOML), or 'phantom' for the generated brain and skin; default: Colin27's "
                      "real brain and skin (Debian package mricron-data), else the phantoms");
  command
      ->add_option("--falloff", choice.falloff,
                   "How every object's dents spread: euclidean (straight line, the paper) or geodesic (along "
                   "the surface); default: as the scene says")
      ->check(CLI::IsMember({"euclidean", "geodesic"}));
}

namespace {

Scene scene_for_file(const std::string& scene_file) {
  if (scene_file == "phantom") return phantom_scene();
  if (!scene_file.empty()) return load_scene(scene_file);
  Progress progress;
  volume::DefaultSceneParams params;
  params.on_note = [](const std::string& note) { std::fprintf(stderr, "palpate: note: %s\n", note.c_str()); };
  params.on_progress = [&](std::string_view object, std::string_view stage, double fraction) {
    progress.update(std::string("building the Colin27 ") + std::string(object), stage, fraction);
  };
  return volume::default_scene(params);
}

}  // namespace

Scene scene_for_option(const SceneChoice& choice) {
  Scene scene = scene_for_file(choice.file);
  if (!choice.falloff.empty()) {
    for (SceneObject& object : scene.objects) {
      object.material.falloff = choice.falloff == "geodesic" ? Falloff::geodesic : Falloff::euclidean;
    }
  }
  return scene;
}

void add_size_options(CLI::App* command, int& width, int& height, const std::string& what) {
  command->add_option("--width", width, what + " width in pixels")
      ->capture_default_str()
      ->check(CLI::Range(64, 8192));
  command->add_option("--height", height, what + " height in pixels")
      ->capture_default_str()
      ->check(CLI::Range(64, 8192));
}

int run_selected(CLI::App& app) {
  const int status = run_in(app);
  return status < 0 ? 0 : status;
}

}  // namespace palpate::cli
