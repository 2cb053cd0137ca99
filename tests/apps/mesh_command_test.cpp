// The `palpate mesh` subcommands, run as a user runs them.
#include <gtest/gtest.h>

#include <fstream>

#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

const std::string cli = PALPATE_CLI;

TEST(MeshCommand, PhantomThenInfoReportsTheTableOneCountsAndTopology) {
  const auto dir = test::scratch_dir("mesh_command_phantom");
  const auto brain = (dir / "brain.ply").string();
  const auto made = test::run_command(cli + " mesh phantom --brain -o " + brain);
  ASSERT_EQ(made.exit_status, 0) << made.output;
  EXPECT_NE(made.output.find("68,856 vertices"), std::string::npos) << made.output;

  const auto info = test::run_command(cli + " mesh info " + brain);
  ASSERT_EQ(info.exit_status, 0) << info.output;
  EXPECT_NE(info.output.find("vertices    68,856"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("triangles   137,708"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("closed      yes"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("manifold    yes"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("load time"), std::string::npos) << info.output;
}

TEST(MeshCommand, ConvertKeepsTheGeometry) {
  const auto dir = test::scratch_dir("mesh_command_convert");
  ASSERT_EQ(test::run_command(cli + " mesh phantom --skin --vertices 2000 -o " + (dir / "skin.ply").string())
                .exit_status,
            0);
  const auto converted = test::run_command(cli + " mesh convert " + (dir / "skin.ply").string() + " " +
                                           (dir / "skin.wrl").string());
  ASSERT_EQ(converted.exit_status, 0) << converted.output;
  const Mesh back = load_mesh(dir / "skin.wrl");
  EXPECT_EQ(back.vertex_count(), 2000u);
  EXPECT_EQ(back.triangle_count(), 3996u);
  EXPECT_TRUE(analyze_topology(back).closed());
}

TEST(MeshCommand, InfoReadsTheExampleSceneFile) {
  const auto info =
      test::run_command(cli + " mesh info " + (test::source_dir() / "examples/scenes/default.toml").string());
  ASSERT_EQ(info.exit_status, 0) << info.output;
  EXPECT_NE(info.output.find("objects     2"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("vertices    159,063"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("components  2"), std::string::npos) << info.output;
}

TEST(MeshCommand, ErrorsGoToStderrWithANonZeroExit) {
  const auto dir = test::scratch_dir("mesh_command_errors");
  const auto missing = test::run_command(cli + " mesh info " + (dir / "absent.ply").string());
  EXPECT_NE(missing.exit_status, 0);
  EXPECT_NE(missing.output.find("absent.ply"), std::string::npos) << missing.output;

  std::ofstream(dir / "garbage.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n";
  const auto garbage = test::run_command(cli + " mesh info " + (dir / "garbage.ply").string());
  EXPECT_NE(garbage.exit_status, 0);
  EXPECT_NE(garbage.output.find("garbage.ply"), std::string::npos) << garbage.output;

  const auto both = test::run_command(cli + " mesh phantom --brain --skin -o " + (dir / "x.ply").string());
  EXPECT_NE(both.exit_status, 0);
  const auto help = test::run_command(cli + " mesh --help");
  EXPECT_EQ(help.exit_status, 0);
  EXPECT_NE(help.output.find("phantom"), std::string::npos);
}

}  // namespace
}  // namespace palpate
