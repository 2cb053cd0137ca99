// The `palpate mesh` subcommands, run as a user runs them.
#include <gtest/gtest.h>

#include <fstream>

#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "palpate/testing/test_shapes.hpp"
#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

const std::string cli = PALPATE_CLI;

TEST(MeshCommand, PhantomThenInfoReportsTheTableOneCountsAndTopology) {
  const auto dir = test::scratch_dir("mesh_command_phantom");
  const auto brain = (dir / "brain.ply").string();
  const auto made = test::run_command(cli + " mesh phantom --brain -o " + brain);
  ASSERT_EQ(made.exit_status, 0) << made.both();
  EXPECT_NE(made.out.find("68,856 vertices"), std::string::npos) << made.both();

  const auto info = test::run_command(cli + " mesh info " + brain);
  ASSERT_EQ(info.exit_status, 0) << info.both();
  EXPECT_NE(info.out.find("vertices    68,856"), std::string::npos) << info.both();
  EXPECT_NE(info.out.find("triangles   137,708"), std::string::npos) << info.both();
  EXPECT_NE(info.out.find("closed      yes"), std::string::npos) << info.both();
  EXPECT_NE(info.out.find("manifold    yes"), std::string::npos) << info.both();
  EXPECT_NE(info.out.find("load time"), std::string::npos) << info.both();
}

TEST(MeshCommand, ConvertKeepsTheGeometry) {
  const auto dir = test::scratch_dir("mesh_command_convert");
  ASSERT_EQ(test::run_command(cli + " mesh phantom --skin --vertices 2000 -o " + (dir / "skin.ply").string())
                .exit_status,
            0);
  const auto converted = test::run_command(cli + " mesh convert " + (dir / "skin.ply").string() + " " +
                                           (dir / "skin.wrl").string());
  ASSERT_EQ(converted.exit_status, 0) << converted.both();
  const Mesh back = load_mesh(dir / "skin.wrl");
  EXPECT_EQ(back.vertex_count(), 2000u);
  EXPECT_EQ(back.triangle_count(), 3996u);
  EXPECT_TRUE(analyze_topology(back).closed());
}

// A flat-shaded torus (three vertices a face, as exporters write it) is one closed surface of genus 1,
// not thousands of loose triangles.
TEST(MeshCommand, InfoReportsTheTopologyOfTheSurfaceNotOfItsShadingSplits) {
  const auto dir = test::scratch_dir("mesh_command_flat");
  const Mesh flat = testing::split_flat(testing::make_torus(30.0f, 12.0f, 24, 12));
  save_mesh(flat, dir / "flat_torus.ply");
  const auto info = test::run_command(cli + " mesh info " + (dir / "flat_torus.ply").string());
  ASSERT_EQ(info.exit_status, 0) << info.both();
  EXPECT_NE(info.out.find(" (288 positions)"), std::string::npos)
      << info.both();  // 24 x 12, of 1,728 corners
  EXPECT_NE(info.out.find("closed      yes"), std::string::npos) << info.both();
  EXPECT_NE(info.out.find("components  1, Euler characteristic 0, genus 1"), std::string::npos)
      << info.both();
}

TEST(MeshCommand, InfoReadsTheExampleSceneFile) {
  const auto info =
      test::run_command(cli + " mesh info " + (test::source_dir() / "examples/scenes/default.toml").string());
  ASSERT_EQ(info.exit_status, 0) << info.both();
  EXPECT_NE(info.out.find("objects     2"), std::string::npos) << info.both();
  EXPECT_NE(info.out.find("vertices    159,063"), std::string::npos) << info.both();
  EXPECT_NE(info.out.find("components  2"), std::string::npos) << info.both();
}

TEST(MeshCommand, ErrorsGoToStderrInPalpatesFormatWithStatusOne) {
  const auto dir = test::scratch_dir("mesh_command_errors");
  const auto absent = (dir / "absent.ply").string();
  const auto missing = test::run_command(cli + " mesh info " + absent);
  EXPECT_EQ(missing.exit_status, 1);
  EXPECT_EQ(missing.out, "");
  EXPECT_EQ(missing.err, "palpate: error: " + absent + ": no such file\n");

  std::ofstream(dir / "garbage.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n";
  const auto garbage = test::run_command(cli + " mesh info " + (dir / "garbage.ply").string());
  EXPECT_EQ(garbage.exit_status, 1);
  EXPECT_EQ(garbage.err.rfind("palpate: error: " + (dir / "garbage.ply").string() + ":", 0), 0u)
      << garbage.err;

  // Command-line mistakes too: palpate's format and status, not the parser's.
  const auto both = test::run_command(cli + " mesh phantom --brain --skin -o " + (dir / "x.ply").string());
  EXPECT_EQ(both.exit_status, 1);
  EXPECT_EQ(both.err, "palpate: error: --brain excludes --skin (see --help)\n");
  const auto range = test::run_command(cli + " demo --width 5");
  EXPECT_EQ(range.exit_status, 1);
  EXPECT_EQ(range.err, "palpate: error: --width: Value 5 not in range 64 to 8192 (see --help)\n");
  const auto no_scene = test::run_command(cli + " demo --scene " + (dir / "absent.toml").string());
  EXPECT_EQ(no_scene.exit_status, 1);
  EXPECT_EQ(no_scene.err,
            "palpate: error: " + (dir / "absent.toml").string() + ": cannot open scene file: no such file\n");

  const auto help = test::run_command(cli + " mesh --help");
  EXPECT_EQ(help.exit_status, 0);
  EXPECT_NE(help.out.find("phantom"), std::string::npos) << help.both();
  EXPECT_EQ(help.err, "");
}

}  // namespace
}  // namespace palpate
