// OBJ, PLY, STL and OFF through assimp, and palpate's two writers read back.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <glm/geometric.hpp>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "palpate/core/shapes.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

std::filesystem::path scratch_file(const std::string& name) {
  static const std::filesystem::path dir = test::scratch_dir("load_mesh_formats");
  return dir / name;
}

std::filesystem::path write_text(const std::string& name, const std::string& text) {
  const auto file = scratch_file(name);
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

// A tetrahedron with outward counter-clockwise faces, in OBJ with one normal per face (`f a//n`):
// assimp splits its 4 positions into 12 vertices; palpate welds them back. Stretched along x, so the
// faces at the origin differ in area: 1 (z = 0), 1 (y = 0) and 1/2 (x = 0).
const char* kTetrahedronObj =
    "v 0 0 0\nv 2 0 0\nv 0 1 0\nv 0 0 1\n"
    "vn 0 0 -1\nvn 0 -1 0\nvn -1 0 0\nvn 0.333333 0.666667 0.666667\n"
    "f 1//1 3//1 2//1\nf 1//2 2//2 4//2\nf 1//3 4//3 3//3\nf 2//4 3//4 4//4\n";

TEST(LoadObj, PerFaceNormalsAreWeldedToTheFilesPositions) {
  const Mesh m = load_mesh(write_text("tetra.obj", kTetrahedronObj));
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.triangle_count(), 4u);
  const MeshTopology topology = analyze_topology(m);
  EXPECT_TRUE(topology.closed());
  EXPECT_TRUE(topology.oriented());
  // The normals disagree at every vertex, so they are area-weighted over the welded faces: at the
  // origin -(1/2, 1, 1) normalised, (-1, -2, -2) / 3 (weighting the faces alike would give (-1, -1, -1)
  // / sqrt(3), 15.8 degrees away).
  const auto origin = std::find(m.positions_mm.begin(), m.positions_mm.end(), glm::vec3(0.0f));
  ASSERT_NE(origin, m.positions_mm.end());
  const glm::vec3 n = m.normals[std::size_t(origin - m.positions_mm.begin())];
  EXPECT_NEAR(n.x, -1.0f / 3.0f, 1e-5f);
  EXPECT_NEAR(n.y, -2.0f / 3.0f, 1e-5f);
  EXPECT_NEAR(n.z, -2.0f / 3.0f, 1e-5f);
}

TEST(LoadObj, PolygonsAreTriangulatedAndGroupsKept) {
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n"
      "o left\nf 1 2 3 4\no right\nf 2 5 6 3\n";
  const Scene scene = load_model(write_text("quads.obj", obj));
  EXPECT_EQ(scene.triangle_count(), 4u);
  EXPECT_EQ(scene.objects.size(), 2u);
}

TEST(LoadStl, SharedCornersAreWelded) {
  std::string stl = "solid tetra\n";
  const char* faces[4][3] = {{"0 0 0", "0 1 0", "1 0 0"},
                             {"0 0 0", "1 0 0", "0 0 1"},
                             {"0 0 0", "0 0 1", "0 1 0"},
                             {"1 0 0", "0 1 0", "0 0 1"}};
  for (const auto& face : faces) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (const char* v : face) stl += std::string("vertex ") + v + "\n";
    stl += "endloop\nendfacet\n";
  }
  stl += "endsolid tetra\n";
  const Mesh m = load_mesh(write_text("tetra.stl", stl));
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_TRUE(analyze_topology(m).closed());
}

TEST(LoadOff, ReadsAnIndexedMesh) {
  const Mesh m = load_mesh(write_text(
      "tetra.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"));
  EXPECT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.triangle_count(), 4u);
}

TEST(LoadPly, AsciiWithColours) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar "
      "int vertex_indices\nend_header\n"
      "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n";
  const Mesh m = load_mesh(write_text("colours.ply", ply));
  ASSERT_EQ(m.colors.size(), 3u);
  for (std::size_t v = 0; v < 3; ++v) {
    const glm::vec3 expected = m.positions_mm[v] == glm::vec3(0, 0, 0)   ? glm::vec3(1, 0, 0)
                               : m.positions_mm[v] == glm::vec3(1, 0, 0) ? glm::vec3(0, 1, 0)
                                                                         : glm::vec3(0, 0, 1);
    EXPECT_EQ(m.colors[v], expected);
  }
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);  // computed: no normals in the file
}

// Triangle by triangle, the corners of `a` and `b` are at the same places (vertex order may differ).
void expect_same_triangles(const Mesh& a, const Mesh& b, float tolerance) {
  ASSERT_EQ(a.triangle_count(), b.triangle_count());
  for (std::size_t i = 0; i < a.indices.size(); ++i) {
    const glm::vec3 pa = a.positions_mm[a.indices[i]], pb = b.positions_mm[b.indices[i]];
    ASSERT_LE(glm::length(pa - pb), tolerance) << "corner " << i;
  }
}

Mesh colored_sphere() {
  Mesh m = make_sphere(25.0f, 1000);
  m.colors.resize(m.vertex_count());
  for (std::size_t v = 0; v < m.vertex_count(); ++v) m.colors[v] = glm::abs(m.normals[v]);
  return m;
}

TEST(SaveMesh, PlyRoundTripKeepsCountsPositionsNormalsAndColours) {
  const Mesh original = colored_sphere();
  const auto file = scratch_file("sphere.ply");
  save_mesh(original, file);
  const Mesh back = load_mesh(file);
  EXPECT_EQ(back.vertex_count(), original.vertex_count());
  expect_same_triangles(original, back, 0.0f);  // binary floats: exact
  ASSERT_EQ(back.colors.size(), back.vertex_count());
  for (std::size_t i = 0; i < original.indices.size(); ++i) {
    const std::uint32_t a = original.indices[i], b = back.indices[i];
    EXPECT_NEAR(glm::distance(original.normals[a], back.normals[b]), 0.0f, 1e-6f);
    EXPECT_LE(glm::length(original.colors[a] - back.colors[b]), 0.5f / 255.0f * 1.8f);  // 8-bit colour
  }
  EXPECT_TRUE(analyze_topology(back).closed());
}

TEST(SaveMesh, VrmlRoundTripKeepsCountsPositionsNormalsAndColours) {
  const Mesh original = colored_sphere();
  const auto file = scratch_file("sphere.wrl");
  save_mesh(original, file);
  const Mesh back = load_mesh(file);
  EXPECT_EQ(back.vertex_count(), original.vertex_count());
  expect_same_triangles(original, back,
                        1e-5f);  // 9 significant digits; Coin's float parsing rounds last bits
  ASSERT_EQ(back.colors.size(), back.vertex_count());
  for (std::size_t i = 0; i < original.indices.size(); ++i) {
    const std::uint32_t a = original.indices[i], b = back.indices[i];
    EXPECT_NEAR(glm::distance(original.normals[a], back.normals[b]), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(original.colors[a], back.colors[b]), 0.0f, 1e-5f);
  }
  EXPECT_TRUE(analyze_topology(back).closed());
}

TEST(SaveMesh, RefusesUnknownExtensionsAndInvalidMeshes) {
  const Mesh sphere = make_sphere(1.0f, 100);
  EXPECT_THROW(save_mesh(sphere, scratch_file("sphere.obj")), Error);
  Mesh broken = sphere;
  broken.indices.push_back(12345);
  broken.indices.push_back(0);
  broken.indices.push_back(1);
  try {
    save_mesh(broken, scratch_file("broken.ply"));
    FAIL() << "saved";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), scratch_file("broken.ply"));
    EXPECT_NE(e.detail().find("uses vertex 12345"), std::string::npos) << e.what();
  }
  EXPECT_THROW(save_mesh(sphere, scratch_file("no_such_folder") / "sphere.ply"), Error);
}

}  // namespace
}  // namespace palpate
