// Every `palpate bench` subcommand once at its smallest, so that a benchmark's code cannot rot unseen:
// exit status, the JSON keys the reports promise, and values that make sense. (No speed is judged
// here: the machines are shared; docs/benchmarks.md holds the figures.)
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

const std::string cli = PALPATE_CLI;

nlohmann::json run_bench(const std::string& arguments, const std::filesystem::path& json) {
  const auto result = test::run_command(cli + " bench " + arguments + " --json " + json.string());
  EXPECT_EQ(result.exit_status, 0) << result.both();
  std::ifstream file(json);
  return nlohmann::json::parse(file);
}

void expect_ordered(const nlohmann::json& p, const std::string& what) {
  for (const char* key : {"p50", "p99", "p999", "max"})
    ASSERT_TRUE(p.contains(key)) << what << " lacks " << key;
  EXPECT_GE(p["p50"].get<double>(), 0.0) << what;
  EXPECT_LE(p["p50"].get<double>(), p["p99"].get<double>()) << what;
  EXPECT_LE(p["p99"].get<double>(), p["p999"].get<double>()) << what;
  EXPECT_LE(p["p999"].get<double>(), p["max"].get<double>()) << what;
}

TEST(BenchCommand, HapticsAtItsSmallestReportsCleanCountsAndARate) {
  const auto json = test::scratch_dir("bench_haptics") / "haptics.json";
  const nlohmann::json report =
      run_bench("haptics --quick --cycles 1 --loop-seconds 0.5 --loads idle memory", json);
  EXPECT_EQ(report["benchmark"], "haptics");
  ASSERT_FALSE(report["rows"].empty());
  int contact_rows = 0;
  std::map<std::string, int> rows_by_load;
  for (const auto& row : report["rows"]) {
    const std::string what = row["scenario"].get<std::string>() + " " + row["mesh"].get<std::string>() + " " +
                             row["load"].get<std::string>();
    ++rows_by_load[row["load"].get<std::string>()];
    EXPECT_GT(row["triangles"].get<int>(), 0) << what;
    EXPECT_GT(row["ticks"].get<int>(), 0) << what;
    expect_ordered(row["tick_us"], what);
    expect_ordered(row["between_us"], what + " between ticks");
    expect_ordered(row["own_tick_us"], what + " own");
    for (const char* key : {"p50", "p99", "p999", "max"})  // each tick's shorter time of two runs
      EXPECT_LE(row["own_tick_us"][key].get<double>(), row["tick_us"][key].get<double>())
          << what << " " << key;
    EXPECT_GT(row["tick_mean_us"].get<double>(), 0.0) << what;
    EXPECT_LE(row["tick_mean_us"].get<double>(), row["tick_us"]["max"].get<double>()) << what;
    const auto& host = row["host_interruptions"];
    EXPECT_GE(host["per_s_over_5us"].get<double>(), host["per_s_over_20us"].get<double>()) << what;
    EXPECT_GE(host["lost_us_per_s"].get<double>(), 5.0 * host["per_s_over_5us"].get<double>()) << what;
    EXPECT_NEAR(row["host_hit_share"].get<double>(),
                host["per_s_over_5us"].get<double>() * row["tick_mean_us"].get<double>() * 1e-6, 1e-12)
        << what;
    if (row["state"] != "contact") continue;
    ++contact_rows;
    const auto& checks = row["checks"];
    for (const char* count :
         {"pop_through_steps", "inward_force_steps", "proxy_inside_steps", "stuck_cycles"}) {
      EXPECT_EQ(checks[count].get<int>(), 0) << what << " " << count;
    }
    EXPECT_GT(checks["max_force_n"].get<double>(), 0.5) << what << ": it pressed";
    EXPECT_LE(checks["capped_ticks"].get<int>(), row["ticks"].get<int>()) << what;
  }
  EXPECT_EQ(contact_rows, 10) << "brain, skin, brain+skin and two sphere-slides, idle and streaming memory";
  EXPECT_EQ(rows_by_load.size(), 2u);
  EXPECT_EQ(rows_by_load["idle"], rows_by_load["memory"]);
  for (const auto& build : report["build"]) EXPECT_NEAR(build["bytes_per_triangle"].get<double>(), 76.0, 2.0);
  ASSERT_EQ(report["loop"].size(), 2u) << "1 kHz idle and loaded";
  for (const auto& loop : report["loop"]) {
    // A sane rate, not a speed target: under a sanitizer on a loaded machine the loop runs slower.
    EXPECT_GT(loop["achieved_hz"].get<double>(), 200.0);
    EXPECT_LT(loop["achieved_hz"].get<double>(), 1100.0);
    expect_ordered(loop["period_error_us"], "period error");
    EXPECT_GE(loop["steal_ms"].get<double>(), 0.0) << "/proc/stat gives the host's steal";
  }
}

TEST(BenchCommand, RenderAtItsSmallestComparesEveryVariant) {
  const auto json = test::scratch_dir("bench_render") / "render.json";
  const nlohmann::json report = run_bench("render --quick --seconds 0.3 --width 160 --height 128", json);
  EXPECT_EQ(report["width"], 160);
  ASSERT_EQ(report["rows"].size(), 18u) << "3 meshes x 6 variants (two of them stereo)";
  for (const auto& row : report["rows"]) {
    EXPECT_GT(row["fps"].get<double>(), 0.0);
    EXPECT_GT(row["frames"].get<int>(), 0);
    EXPECT_GT(row["cpu_ms"].get<double>(), 0.0);
    EXPECT_TRUE(row.contains("gpu_ms"));
  }
}

// The toolkits' rows: Coin3D on palpate's headless context, VTK in an X window (under Xvfb here).
TEST(BenchCommand, RenderWithToolkitsComparesEachToolkitWithItsOwnPlainDrawing) {
  const auto json = test::scratch_dir("bench_render_toolkits") / "render.json";
  const auto result =
      test::run_command("xvfb-run -a " + cli +
                        " bench render --quick --toolkits --seconds 0.2 --width 160 --height 128 "
                        "--json " +
                        json.string());
  ASSERT_EQ(result.exit_status, 0) << result.both();
  std::ifstream file(json);
  const nlohmann::json report = nlohmann::json::parse(file);
  std::map<std::string, int> rows_per_toolkit;
  for (const auto& row : report["rows"]) {
    rows_per_toolkit[row["toolkit"].get<std::string>() + " " + row["variant"].get<std::string>()] += 1;
    EXPECT_GT(row["fps"].get<double>(), 0.0);
    EXPECT_GT(row["frames"].get<int>(), 0);
  }
  for (const char* variant : {"palpate deform", "palpate plain", "coin plain", "coin deform",
                              "coin deform-per-fragment", "vtk plain", "vtk deform"})
    EXPECT_EQ(rows_per_toolkit[variant], 3) << variant << ": one row per Table I mesh";
}

TEST(BenchCommand, Table1AtItsSmallestGivesThePapersRows) {
  const auto dir = test::scratch_dir("bench_table1");
  const nlohmann::json report =
      run_bench("table1 --headless --scene phantom --seconds 0.5 --width 160 --height 128 --plot ''",
                dir / "table1.json");
  ASSERT_EQ(report["rows"].size(), 3u);
  const char* models[] = {"Brain", "Skin", "Skin + Brain"};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& row = report["rows"][i];
    EXPECT_EQ(row["model"], models[i]);
    EXPECT_GT(row["graphics_fps"].get<double>(), 0.0);
    // The loop keeps its 1 ms grid: most ticks start on time. A tick the machine preempts is lost, not
    // caught up, so the rate over half a second drops when the tests share the two cores (seen at
    // 1000 +- 100 failing in a parallel run): the rate is only bounded.
    EXPECT_LE(row["haptics"]["period_error_us"]["p50"].get<double>(), 100.0);
    EXPECT_GT(row["haptics_hz"].get<double>(), 500.0);
    EXPECT_LE(row["haptics_hz"].get<double>(), 1010.0);
    EXPECT_GT(row["cpu_naive_fps"].get<double>(), 0.0);
    EXPECT_GT(row["max_force_n"].get<double>(), 0.0) << "the probe was in contact";
  }
}

}  // namespace
}  // namespace palpate

namespace palpate {
namespace {

TEST(BenchCommand, GeodesicAtItsSmallestReportsEveryRowAndFold) {
  const auto json = test::scratch_dir("bench_geodesic") / "geodesic.json";
  const nlohmann::json report =
      run_bench("geodesic --quick --headless --surfaces phantom --width 160 --height 128", json);
  EXPECT_EQ(report["benchmark"], "geodesic");
  ASSERT_EQ(report["rows"].size(), 3u);  // sigma 2, 4, 8 mm
  for (const auto& row : report["rows"]) {
    for (const char* key : {"mesh", "vertices", "sigma_mm", "contacts", "bleed_euclidean", "bleed_geodesic",
                            "weight_error_mean", "weight_error_max", "weight_error_contacts_over_0_03",
                            "distance_ms", "update_ms", "upload_ms", "frame_overhead_pct"})
      ASSERT_TRUE(row.contains(key)) << key;
    EXPECT_EQ(row["mesh"], "phantom brain");
    EXPECT_EQ(row["bleed_geodesic"], 0) << "the geodesic falloff bleeds across a sulcus";
    // A wall gives way only where the pushed surface would come within a fifth of its gap of it: a few
    // vertices in the phantom's narrowest sulci at sigma 8 (2 of its 10,224 straight-line bleeders).
    EXPECT_LE(row["bleed_geodesic_with_walls"].get<int>() * 100, row["bleed_euclidean"].get<int>())
        << "a 1 mm press moved walls far along the phantom";
    EXPECT_GT(row["bleed_euclidean"].get<int>(), 0)
        << "the phantom's sulci should make the straight line bleed";
    EXPECT_LE(row["weight_error_max"].get<double>(), 0.1);
    EXPECT_LE(row["update_ms"]["p50"].get<double>(), row["update_ms"]["p99"].get<double>());
  }
  ASSERT_EQ(report["folds"].size(), 18u);  // six ways of moving the surface, at 1, 2 and 3 sigma
  for (const auto& fold : report["folds"]) {
    for (const char* key : {"mesh", "falloff", "depth_over_sigma", "presses", "self_intersecting_triangles",
                            "inverted_triangles", "wall_vertices_given_way"})
      ASSERT_TRUE(fold.contains(key)) << key;
    // Only the renderer's choice lets walls give way, and on the phantom some do from 2 sigma on.
    const bool walls = fold["direction"].get<std::string>().find("walls give way") != std::string::npos;
    if (!walls) {
      EXPECT_EQ(fold["wall_vertices_given_way"], 0) << fold.dump();
    } else if (fold["depth_over_sigma"].get<double>() >= 2.0) {
      EXPECT_GT(fold["wall_vertices_given_way"].get<int>(), 0) << fold.dump();
    }
  }
}

}  // namespace
}  // namespace palpate
