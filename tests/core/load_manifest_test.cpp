// Every mesh file of ../shared/data/manifest.tsv loads with the triangle count the manifest lists
// (counted there by Coin, assimp and independent parsers), or fails with a message that says which
// feature palpate does not support.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "palpate/core/error.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

struct ManifestRow {
  std::string path, format;
  long triangles_all = -1;  // -1: "-" in the manifest
  long vertices = -1;
};

long number_or_none(const std::string& field) {
  return field == "-" ? -1 : std::stol(field);
}

std::vector<ManifestRow> manifest_rows() {
  std::vector<ManifestRow> rows;
  if (const auto data = test::shared_data_dir()) {
    std::ifstream in(*data / "manifest.tsv");
    std::string line;
    std::getline(in, line);  // header: path format triangles_ifs triangles_all vertices notes
    while (std::getline(in, line)) {
      std::vector<std::string> fields;
      std::stringstream split(line);
      for (std::string field; std::getline(split, field, '\t');) fields.push_back(field);
      if (fields.size() < 5) continue;
      rows.push_back({fields[0], fields[1], number_or_none(fields[3]), number_or_none(fields[4])});
    }
  }
  if (rows.empty()) rows.push_back({});  // one placeholder that skips, so the suite always runs
  return rows;
}

// Files palpate does not load, and the words its message must contain.
const std::map<std::string, std::string>& expected_failures() {
  static const std::map<std::string, std::string> failures{
      {"vrml/castle_tesselated_plane_proto.wrl", "has no triangle geometry"},  // the manifest's 0
      {"x3d/castle_axis.x3d.gz", "assimp found no triangle meshes"},  // assimp drops Collision's children
      {"x3d/castle_blender_monkey.x3d", "ImageTexture"},              // assimp rejects the texture url
      {"x3d/castle_indexed_face_set_colors.x3dv", "X3D classic encoding (.x3dv) is not supported"},
      {"volumes/spm12_single_subj_T1.nii", "is a volume image"},
      {"volumes/spm12_avg152T1.nii", "is a volume image"},
      {"volumes/mni_icbm152_t1_tal_nlin_sym_09a_converted.nii.gz", "is a volume image"},
  };
  return failures;
}

// Files whose loaded vertex count is the manifest's: one vertex per file vertex. Elsewhere palpate
// splits vertices where normals or colours are discontinuous (VRML97's default creaseAngle 0 makes
// every face flat) and Coin's primitives have seams, so the counts are larger by design.
bool vertex_count_is_faithful(const ManifestRow& row) {
  return row.format == "OBJ" || row.format.rfind("PLY", 0) == 0 || row.format.rfind("GIfTI", 0) == 0 ||
         row.path == "vrml/castle_teapot.wrl" || row.path == "vrml/castle_collisions.wrl";
}

std::string test_name(const ManifestRow& row) {
  std::string name = row.path.empty() ? "absent" : row.path;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

class ManifestFile : public ::testing::TestWithParam<ManifestRow> {};

TEST_P(ManifestFile, LoadsWithTheListedTriangleCountOrSaysWhatIsUnsupported) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const ManifestRow& row = GetParam();
  if (row.path.empty()) GTEST_SKIP() << "manifest.tsv has no rows";
  const std::filesystem::path file = data / row.path;
  std::vector<std::string> warnings;
  LoadParams options;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };

  if (const auto failure = expected_failures().find(row.path); failure != expected_failures().end()) {
    try {
      load_model(file, options);
      FAIL() << row.path << " loaded, but palpate was expected to refuse it";
    } catch (const Error& e) {
      EXPECT_EQ(e.file(), file);
      EXPECT_NE(std::string(e.what()).find(failure->second), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(row.path.substr(row.path.find('/') + 1)), std::string::npos)
          << e.what();
    }
    return;
  }

  const Scene scene = load_model(file, options);
  EXPECT_EQ(static_cast<long>(scene.triangle_count()), row.triangles_all) << row.path;
  if (vertex_count_is_faithful(row)) {
    EXPECT_EQ(static_cast<long>(scene.vertex_count()), row.vertices) << row.path;
  }
  for (const SceneObject& object : scene.objects) {
    EXPECT_EQ(object.source, file);
    EXPECT_EQ(object.transform, glm::mat4(1.0f));
  }
}

INSTANTIATE_TEST_SUITE_P(SharedData, ManifestFile, ::testing::ValuesIn(manifest_rows()),
                         [](const ::testing::TestParamInfo<ManifestRow>& param) {
                           return test_name(param.param);
                         });

// The closedness the manifest states survives loading (welding restored OBJ's split positions).
TEST(ManifestTopology, ClosedSurfacesStayClosedAndOutward) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  for (const char* path :
       {"surfaces/odedstein_skull_low_resolution.obj", "canonical/odedstein_bunny_manifold.obj",
        "surfaces/fsaverage5_pial_left.gii.gz", "surfaces/spm12_cortex_20484.surf.gii",
        "surfaces/spm12_scalp_2562.surf.gii", "canonical/odedstein_armadillo.obj"}) {
    SCOPED_TRACE(path);
    const Mesh mesh = load_mesh(data / path);
    const MeshTopology topology = analyze_topology(mesh);
    EXPECT_TRUE(topology.closed());
    EXPECT_TRUE(topology.oriented());
    // Outward: the signed volume of a closed surface with counter-clockwise faces seen from
    // outside is positive.
    double volume = 0.0;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      volume += glm::dot(glm::dvec3(mesh.positions_mm[mesh.indices[t]]),
                         glm::cross(glm::dvec3(mesh.positions_mm[mesh.indices[t + 1]]),
                                    glm::dvec3(mesh.positions_mm[mesh.indices[t + 2]])));
    }
    EXPECT_GT(volume, 0.0);
  }
}

TEST(ManifestTopology, SpmCortexHasTwoComponentsOnlyWhenReadColumnMajor) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const MeshTopology topology = analyze_topology(load_mesh(data / "surfaces/spm12_cortex_8196.surf.gii"));
  EXPECT_EQ(topology.components, 2u);
  EXPECT_EQ(topology.euler_characteristic, 4);
  EXPECT_EQ(topology.degenerate_triangles, 0u);
}

TEST(ManifestTopology, BunnyKeepsItsHolesAndItsUnreferencedVertices) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  const MeshTopology topology = analyze_topology(load_mesh(data / "canonical/bun_zipper.ply"));
  EXPECT_EQ(topology.boundary_edges, 223u);
  EXPECT_EQ(topology.unreferenced_vertices, 1113u);  // as the manifest says: the file's vertices, all of them
  EXPECT_EQ(topology.components, 1u);
}

}  // namespace
}  // namespace palpate
