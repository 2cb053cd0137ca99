// palpate bench: the group of benchmarks. Each benchmark lives in its own file and adds itself with
// add_bench_command(app).add_subcommand(...).
#include "commands.hpp"

namespace palpate::cli {

CLI::App& add_bench_command(CLI::App& app) {
  const auto existing = app.get_subcommands([](CLI::App* sub) { return sub->get_name() == "bench"; });
  if (!existing.empty()) return *existing.front();
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks: a printed table and --json FILE");
  bench->require_subcommand(1);
  return *bench;
}

}  // namespace palpate::cli
