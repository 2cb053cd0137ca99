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

// --scene FILE|phantom (a scene file; "phantom": the generated phantoms; empty: the default scene).
void add_scene_option(CLI::App* command, std::string& scene_file);
// The scene --scene names: a scene file, the phantoms, or (empty) the default scene: Colin27's brain
// and skin, built on first use with progress on stderr and cached, or the phantoms with a note.
Scene scene_for_option(const std::string& scene_file);
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

}  // namespace palpate::cli
