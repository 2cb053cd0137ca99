#include "commands.hpp"

#include <map>

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

void add_scene_option(CLI::App* command, std::string& scene_file) {
  command->add_option("--scene", scene_file,
                      "Scene file (TOML); default: the built-in brain and skin phantoms");
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
