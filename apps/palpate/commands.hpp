#pragma once
// Subcommand registration: each add_* registers its options and an action run after parsing.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

#include "palpate/core/scene.hpp"

namespace palpate::cli {

// Registers `action` to run when `command` was selected on the command line.
void on_selected(CLI::App* command, std::function<int()> action);
// Runs the action of the selected subcommand; returns its exit status.
int run_selected(CLI::App& app);

// --scene FILE|phantom (a scene file; "phantom": the generated phantoms; empty: the default scene) and
// --falloff euclidean|geodesic (every object's; empty: as the scene says).
struct SceneChoice {
  std::string file, falloff;
};
void add_scene_options(CLI::App* command, SceneChoice& choice);
// The scene --scene names: a scene file, the phantoms, or (empty) the default scene: Colin27's brain
// and skin, built on first use with progress on stderr and cached, or the phantoms with a note; with
// --falloff's falloff on every object.
Scene scene_for_option(const SceneChoice& choice);
// --width and --height of a frame or window ("Frame", "Window"), 64 to 8192 pixels.
void add_size_options(CLI::App* command, int& width, int& height, const std::string& what);

void add_demo_command(CLI::App& app);
void add_mesh_command(CLI::App& app);
void add_mesh_from_volume_command(CLI::App& mesh_group);
void add_scene_command(CLI::App& app);
void add_view_command(CLI::App& app);

// The `bench` group, made on the first call and returned on later ones: each benchmark adds its
// subcommand to it (bench haptics, bench render, ...).
CLI::App& add_bench_command(CLI::App& app);
void add_bench_haptics_command(CLI::App& app);
void add_bench_render_command(CLI::App& app);
void add_bench_table1_command(CLI::App& app);
void add_bench_geodesic_command(CLI::App& app);

}  // namespace palpate::cli
