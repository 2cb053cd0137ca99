// palpate mesh from-volume and scene from-volume on the real volumes of ../shared/data: the printed
// summary, the files written, and errors in palpate's format with status 1.
#include <gtest/gtest.h>

#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "palpate/core/scene_file.hpp"
#include "run_command.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

const std::string cli = PALPATE_CLI;

TEST(MeshFromVolume, WritesAClosedHeadAndPrintsEachStage) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const auto out = test::scratch_dir("mesh_from_volume") / "head.ply";
  const auto scan = data / "volumes/spm12_single_subj_T1.nii";
  const auto result = test::run_command(cli + " mesh from-volume " + scan.string() +
                                        " --smooth 1 --largest --closed --vertices 20000 -o " + out.string());
  ASSERT_EQ(result.exit_status, 0) << result.both();
  const std::vector<std::string> expected_lines = {
      "91 x 109 x 91 voxels, NIfTI sform (code 2), intensities 0 .. 0.996078, threshold",
      "(from the histogram; --iso to choose)",
      "  smooth ",
      "  close ",
      "  isosurface ",
      "  largest piece ",
      "  decimate ",
      "closed yes (0 boundary edges), manifold yes",
      "wrote " + out.string()};
  for (const std::string& expected : expected_lines)
    EXPECT_NE(result.out.find(expected), std::string::npos) << expected << "\n" << result.both();
  EXPECT_NE(result.err.find("palpate: decimate"), std::string::npos) << "progress goes to stderr";
  const Mesh mesh = load_mesh(out);
  EXPECT_NEAR(double(mesh.vertex_count()), 20000.0, 200.0);
  EXPECT_TRUE(analyze_topology(mesh).closed());
}

TEST(MeshFromVolume, BadInputIsAnErrorInPalpatesFormat) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const auto scan = data / "volumes/spm12_single_subj_T1.nii";
  const auto out = test::scratch_dir("mesh_from_volume_errors") / "x.ply";
  const auto high =
      test::run_command(cli + " mesh from-volume " + scan.string() + " --iso 5 -o " + out.string());
  EXPECT_EQ(high.exit_status, 1);
  EXPECT_EQ(high.err, "palpate: error: " + scan.string() +
                          ": threshold 5 is outside the intensity range (0, 0.996078)\n");
  const auto absent = test::run_command(cli + " mesh from-volume absent.nii.gz -o " + out.string());
  EXPECT_EQ(absent.exit_status, 1);
  EXPECT_EQ(absent.err, "palpate: error: absent.nii.gz: no such file or folder\n");
}

TEST(SceneFromVolume, WritesASceneOfSkinAndBrainThatLoads) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const auto scene_file = test::scratch_dir("scene_from_volume") / "head.toml";
  const auto result = test::run_command(
      cli + " scene from-volume " + (data / "volumes/spm12_avg152T1.nii").string() + " --brain " +
      (data / "volumes/mni_icbm152_t1_tal_nlin_sym_09a_converted.nii.gz").string() +
      " --skin-vertices 6000 --brain-vertices 5000 -o " + scene_file.string());
  ASSERT_EQ(result.exit_status, 0) << result.both();
  EXPECT_NE(result.out.find("(from the histogram; --iso-skin to choose)"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("(from the histogram; --iso-brain to choose)"), std::string::npos) << result.out;
  const Scene scene = load_scene(scene_file);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].name, "brain");
  EXPECT_NEAR(double(scene.objects[0].mesh.vertex_count()), 5000.0, 50.0);
  EXPECT_NEAR(double(scene.objects[1].mesh.vertex_count()), 6000.0, 60.0);
  EXPECT_EQ(scene.objects[1].material.sigma_mm, 14.0f);
}

}  // namespace
}  // namespace palpate
