// palpate: the command-line front end. Each subcommand lives in its own file and is built only from
// the library's public API.
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "commands.hpp"
#include "palpate/core/error.hpp"

int main(int argc, char** argv) {
  // Mesa's llvmpipe frees its binned scene (tens of MB in 64 KB blocks) after every frame; with glibc's
  // default trim threshold the heap then shrinks and grows back each frame, page faults and zeroing
  // taking time from every frame. Keeping freed memory in the process costs nothing on a GPU driver.
  // glibc's own MALLOC_TRIM_THRESHOLD_, when set, wins (docs/benchmarks.md measures both this way).
  if (!std::getenv("MALLOC_TRIM_THRESHOLD_")) mallopt(M_TRIM_THRESHOLD, 1 << 30);
  CLI::App app{"palpate: GPU visual deformation for point-based haptic applications"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "palpate 0.1.0");
  palpate::cli::add_demo_command(app);
  palpate::cli::add_mesh_command(app);
  palpate::cli::add_scene_command(app);
  palpate::cli::add_view_command(app);
  palpate::cli::add_bench_command(app);
  palpate::cli::add_bench_haptics_command(app);
  palpate::cli::add_bench_render_command(app);
  palpate::cli::add_bench_table1_command(app);
  palpate::cli::add_bench_geodesic_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Every error in palpate's one format and status; the usage is one --help away.
    std::fprintf(stderr, "palpate: error: %s (see --help)\n", e.what());
    return 1;
  }
  try {
    return palpate::cli::run_selected(app);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palpate: error: %s\n", e.what());
    return 1;
  }
}
