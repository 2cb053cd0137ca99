// Small hand-written VRML97, VRML 1.0 and Inventor files, each checking one thing Coin and palpate
// must do right, against values worked out by hand.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "palpate/core/error.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

std::filesystem::path write_text(const std::string& name, const std::string& text) {
  const auto file = test::scratch_dir("load_vrml") / name;
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

// A unit cube as one IndexedFaceSet: 8 points, 6 quads, counter-clockwise seen from outside.
std::string cube_face_set(const std::string& extra_fields = "") {
  return "IndexedFaceSet { " + extra_fields +
         " coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 0 0 1, 1 0 1, 1 1 1, 0 1 1] }"
         " coordIndex [0 3 2 1 -1, 4 5 6 7 -1, 0 1 5 4 -1, 2 3 7 6 -1, 1 2 6 5 -1, 0 4 7 3 -1] }";
}

double signed_volume(const Mesh& m) {
  double volume = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    volume += glm::dot(glm::dvec3(m.positions_mm[m.indices[t]]),
                       glm::cross(glm::dvec3(m.positions_mm[m.indices[t + 1]]),
                                  glm::dvec3(m.positions_mm[m.indices[t + 2]]))) /
              6.0;
  }
  return volume;
}

TEST(LoadVrml, FacetedCubeByDefaultCreaseAngleZero) {
  const Mesh m =
      load_mesh(write_text("cube.wrl", "#VRML V2.0 utf8\nShape { geometry " + cube_face_set() + " }\n"));
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_EQ(m.vertex_count(), 24u);  // 4 per face: flat normals split the corners
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-6);
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    // Each normal is a face axis: one component is ±1.
    EXPECT_NEAR(std::abs(m.normals[v].x) + std::abs(m.normals[v].y) + std::abs(m.normals[v].z), 1.0f, 1e-6f);
    EXPECT_GT(glm::dot(m.normals[v], m.positions_mm[v] - glm::vec3(0.5f)), 0.0f);  // outward
  }
}

TEST(LoadVrml, SmoothCubeWithLargeCreaseAngleIsClosed) {
  const Mesh m = load_mesh(write_text(
      "smooth.wrl", "#VRML V2.0 utf8\nShape { geometry " + cube_face_set("creaseAngle 3.14") + " }\n"));
  EXPECT_EQ(m.vertex_count(), 8u);
  EXPECT_TRUE(analyze_topology(m).closed());
  for (std::size_t v = 0; v < 8; ++v) {
    // Area-weighted over the corner's faces: two triangles on one face, one on another, ... the
    // normal points away from the centre, into the corner's octant.
    const glm::vec3 out = m.positions_mm[v] - glm::vec3(0.5f);
    EXPECT_GT(glm::dot(m.normals[v], glm::normalize(out)), 0.8f);
  }
}

TEST(LoadVrml, CreaseAngleSplitsOnlySharpEdges) {
  // A roof of two quads meeting at 10 degrees off flat, and a wall at 90 degrees to one of them.
  const float a = 10.0f * std::numbers::pi_v<float> / 180.0f;
  const std::string z = std::to_string(std::sin(a));
  const std::string x = std::to_string(1.0f + std::cos(a));
  const std::string points =
      "0 0 0, 1 0 0, 1 1 0, 0 1 0, " + x + " 0 " + z + ", " + x + " 1 " + z + ", 0 0 -1, 0 1 -1";
  const auto face_set = [&](const std::string& crease) {
    return "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { creaseAngle " + crease +
           " coord Coordinate { point [" + points +
           "] } coordIndex [0 1 2 3 -1, 1 4 5 2 -1, 6 0 3 7 -1] } }\n";
  };
  // 0.5 rad (28.6°) joins the roof (10°) but not the wall (90°): the edge 0-3 is split.
  const Mesh joined = load_mesh(write_text("crease_joined.wrl", face_set("0.5")));
  EXPECT_EQ(joined.vertex_count(), 10u);  // 6 roof + 4 wall
  // 0.1 rad (5.7°) splits the roof too.
  const Mesh split = load_mesh(write_text("crease_split.wrl", face_set("0.1")));
  EXPECT_EQ(split.vertex_count(), 12u);
}

TEST(LoadVrml, ColoursPerFaceSplitVerticesAndPerVertexKeepThem) {
  const std::string text =
      "#VRML V2.0 utf8\n"
      "Shape { geometry IndexedFaceSet { creaseAngle 3 coord DEF C Coordinate { point [0 0 0, 1 0 0, 1 1 0, "
      "0 1 0] }\n"
      "  coordIndex [0 1 2 -1, 0 2 3 -1] colorPerVertex FALSE color Color { color [1 0 0, 0 1 0] } } }\n"
      "Transform { translation 5 0 0 children Shape { geometry IndexedFaceSet { creaseAngle 3 coord USE C\n"
      "  coordIndex [0 1 2 3 -1] color Color { color [1 0 0, 0 1 0, 0 0 1, 1 1 1] } } } }\n";
  const Scene scene = load_model(write_text("colours.wrl", text));
  ASSERT_EQ(scene.objects.size(), 2u);
  const Mesh& per_face = scene.objects[0].mesh;
  EXPECT_EQ(per_face.vertex_count(), 6u);  // the shared diagonal's two corners split by colour
  ASSERT_EQ(per_face.colors.size(), 6u);
  for (std::size_t t = 0; t < 2; ++t) {
    const glm::vec3 expected = t == 0 ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(per_face.colors[per_face.indices[3 * t + c]], expected);
  }
  const Mesh& per_vertex = scene.objects[1].mesh;
  EXPECT_EQ(per_vertex.vertex_count(), 4u);
  ASSERT_EQ(per_vertex.colors.size(), 4u);
  for (std::size_t v = 0; v < 4; ++v) {
    const glm::vec3 p = per_vertex.positions_mm[v] - glm::vec3(5, 0, 0);  // the Transform is baked in
    const glm::vec3 expected = p == glm::vec3(0, 0, 0)   ? glm::vec3(1, 0, 0)
                               : p == glm::vec3(1, 0, 0) ? glm::vec3(0, 1, 0)
                               : p == glm::vec3(1, 1, 0) ? glm::vec3(0, 0, 1)
                                                         : glm::vec3(1, 1, 1);
    EXPECT_EQ(per_vertex.colors[v], expected);
  }
}

TEST(LoadVrml, MaterialColourWithoutVertexColours) {
  const Scene scene = load_model(write_text("material.wrl",
                                            "#VRML V2.0 utf8\nShape { appearance Appearance { material "
                                            "Material { diffuseColor 0.2 0.4 0.6 } } geometry " +
                                                cube_face_set() + " }\n"));
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_TRUE(scene.objects[0].mesh.colors.empty());
  EXPECT_NEAR(scene.objects[0].material.color.r, 0.2f, 1e-6f);
  EXPECT_NEAR(scene.objects[0].material.color.g, 0.4f, 1e-6f);
  EXPECT_NEAR(scene.objects[0].material.color.b, 0.6f, 1e-6f);
}

TEST(LoadVrml, DefUseInstancesGetTheirOwnTransforms) {
  const std::string text =
      "#VRML V2.0 utf8\n"
      "DEF Box1 Transform { children DEF Cube Shape { geometry " +
      cube_face_set() +
      " } }\n"
      "Transform { translation 10 0 0 rotation 0 0 1 1.5707963 scale 2 2 2 children USE Cube }\n";
  const Scene scene = load_model(write_text("def_use.wrl", text));
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].name, "Cube");
  const Bounds second = bounds(scene.objects[1].mesh);
  // Rotated 90° about z then scaled by 2 then moved by 10 in x: x in [8, 10], y in [0, 2], z in [0, 2].
  EXPECT_NEAR(second.min_mm.x, 8.0f, 1e-5f);
  EXPECT_NEAR(second.max_mm.x, 10.0f, 1e-5f);
  EXPECT_NEAR(second.max_mm.y, 2.0f, 1e-5f);
  EXPECT_NEAR(second.max_mm.z, 2.0f, 1e-5f);
  EXPECT_NEAR(signed_volume(scene.objects[1].mesh), 8.0, 1e-4);
}

TEST(LoadVrml, MirroringTransformAndClockwiseFacesStayOutward) {
  const std::string text =
      "#VRML V2.0 utf8\n"
      "Transform { scale -1 1 1 children Shape { geometry " +
      cube_face_set() +
      " } }\n"
      "Transform { translation 5 0 0 children Shape { geometry IndexedFaceSet { ccw FALSE"
      " coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 0 0 1, 1 0 1, 1 1 1, 0 1 1] }"
      " coordIndex [0 1 2 3 -1, 4 7 6 5 -1, 0 4 5 1 -1, 2 6 7 3 -1, 1 5 6 2 -1, 0 3 7 4 -1] } } }\n";
  const Scene scene = load_model(write_text("mirror.wrl", text));
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_NEAR(signed_volume(scene.objects[0].mesh), 1.0, 1e-6);
  EXPECT_NEAR(signed_volume(scene.objects[1].mesh), 1.0, 1e-6);
}

TEST(LoadVrml, ExplicitNormalsAreKept) {
  const std::string text =
      "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {"
      " coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] } coordIndex [0 1 2 3 -1]"
      " normal Normal { vector [0 0.6 0.8] } normalPerVertex FALSE } }\n";
  const Mesh m = load_mesh(write_text("normals.wrl", text));
  EXPECT_EQ(m.vertex_count(), 4u);
  for (const glm::vec3& n : m.normals) {
    EXPECT_NEAR(n.y, 0.6f, 1e-6f);
    EXPECT_NEAR(n.z, 0.8f, 1e-6f);
  }
}

TEST(LoadVrml, PrimitivesAtCoinsDefaultComplexity) {
  // Coin's tessellation at its default complexity 0.5: a Sphere is 390 triangles (as in the
  // manifest: 104 spheres = 40,560), a default Cone 38 and Cylinder 76 (with their caps), a Box 12.
  const std::string text =
      "#VRML V2.0 utf8\nShape { geometry Sphere { radius 2 } }\nShape { geometry Box { size 1 2 3 } }\n"
      "Shape { geometry Cone { } }\nShape { geometry Cylinder { } }\n";
  const Scene scene = load_model(write_text("primitives.wrl", text));
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_EQ(scene.objects[0].mesh.triangle_count(), 390u);
  EXPECT_EQ(scene.objects[1].mesh.triangle_count(), 12u);
  EXPECT_EQ(scene.objects[2].mesh.triangle_count(), 38u);
  EXPECT_EQ(scene.objects[3].mesh.triangle_count(), 76u);
  for (const glm::vec3& p : scene.objects[0].mesh.positions_mm) EXPECT_NEAR(glm::length(p), 2.0f, 1e-5f);
  const Bounds box = bounds(scene.objects[1].mesh);
  EXPECT_EQ(box.size_mm(), glm::vec3(1, 2, 3));
  EXPECT_GT(signed_volume(scene.objects[0].mesh), 0.0);
  EXPECT_NEAR(signed_volume(scene.objects[1].mesh), 6.0, 1e-5);
}

TEST(LoadVrml, CollisionProxyIsNotDrawn) {
  const std::string text = "#VRML V2.0 utf8\nCollision { children Shape { geometry " + cube_face_set() +
                           " } proxy Shape { geometry Sphere { } } }\n";
  const Scene scene = load_model(write_text("collision.wrl", text));
  EXPECT_EQ(scene.triangle_count(), 12u);
}

TEST(LoadVrml, TextAndLinesAreSkippedWithWarnings) {
  const std::string text =
      "#VRML V2.0 utf8\nShape { geometry Text { string \"hello\" } }\n"
      "Shape { geometry IndexedLineSet { coord Coordinate { point [0 0 0, 1 0 0] } coordIndex [0 1] } }\n"
      "Shape { geometry " +
      cube_face_set() + " }\n";
  std::vector<std::string> warnings;
  LoadParams options;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const Scene scene = load_model(write_text("text.wrl", text), options);
  EXPECT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.triangle_count(), 12u);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("skipped 1 text node"), std::string::npos);
  EXPECT_NE(warnings[1].find("skipped 1 line or point set"), std::string::npos);
}

TEST(LoadVrml, UnknownFieldsAreDroppedWithAWarning) {
  const std::string text =
      "#VRML V2.0 utf8\n"
      "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 mirror 0.5 }\n"
      "  blendMode BlendMode { destFactor \"ONE\" } }\n"
      "  geometry " +
      cube_face_set() + " }\n";
  std::vector<std::string> warnings;
  LoadParams options;
  options.on_warning = [&](const std::string& w) { warnings.push_back(w); };
  const Scene scene = load_model(write_text("unknown.wrl", text), options);
  EXPECT_EQ(scene.triangle_count(), 12u);
  EXPECT_EQ(scene.objects[0].material.color, glm::vec3(1, 0, 0));
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find(":2: dropped the non-standard field \"mirror\" of Material"), std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find(":3: dropped the non-standard field \"blendMode\" of Appearance"),
            std::string::npos)
      << warnings[1];
}

TEST(LoadVrml, Vrml1SeparatorStateMaterialBindingAndClockwiseHints) {
  const std::string text =
      "#VRML V1.0 ascii\n"
      "Separator {\n"
      "  ShapeHints { vertexOrdering CLOCKWISE }\n"
      "  Material { diffuseColor [1 0 0, 0 0 1] } MaterialBinding { value PER_FACE }\n"
      "  Coordinate3 { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }\n"
      "  Translation { translation 0 0 3 }\n"
      "  IndexedFaceSet { coordIndex [0 3 2 -1, 0 2 1 -1] }\n"
      "}\n";
  const Mesh m = load_mesh(write_text("vrml1.wrl", text));
  EXPECT_EQ(m.triangle_count(), 2u);
  ASSERT_EQ(m.colors.size(), m.vertex_count());
  EXPECT_EQ(m.colors[m.indices[0]], glm::vec3(1, 0, 0));
  EXPECT_EQ(m.colors[m.indices[3]], glm::vec3(0, 0, 1));
  for (const glm::vec3& p : m.positions_mm) EXPECT_EQ(p.z, 3.0f);
  // Clockwise in the file, so reversed: the front faces +z.
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(LoadVrml, InventorFileByHeaderWhateverItsName) {
  const std::string text = "#Inventor V2.1 ascii\nSeparator { Cube { width 2 height 2 depth 2 } }\n";
  const Mesh m = load_mesh(write_text("cube.model", text));
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_NEAR(signed_volume(m), 8.0, 1e-5);
}

TEST(LoadVrml, GzipIsDetectedByContentNotName) {
  const std::string text = "#VRML V2.0 utf8\nShape { geometry " + cube_face_set() + " }\n";
  std::string compressed(compressBound(static_cast<uLong>(text.size())) + 64, '\0');
  z_stream stream{};
  ASSERT_EQ(deflateInit2(&stream, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  stream.avail_in = static_cast<uInt>(text.size());
  stream.next_out = reinterpret_cast<Bytef*>(compressed.data());
  stream.avail_out = static_cast<uInt>(compressed.size());
  ASSERT_EQ(deflate(&stream, Z_FINISH), Z_STREAM_END);
  compressed.resize(stream.total_out);
  deflateEnd(&stream);
  EXPECT_EQ(load_mesh(write_text("plain_name.wrl", compressed)).triangle_count(), 12u);
  EXPECT_EQ(load_mesh(write_text("zipped.wrz", compressed)).triangle_count(), 12u);
}

TEST(LoadVrml, BadColourIndexIsAnError) {
  const std::string text =
      "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0] }"
      " coordIndex [0 1 2] colorPerVertex FALSE color Color { color [1 0 0] } colorIndex [3] } }\n";
  try {
    load_model(write_text("bad_colour.wrl", text));
    FAIL() << "loaded";
  } catch (const Error& e) {
    EXPECT_NE(e.detail().find("colorIndex[0] is 3, but Color.color has 1 entries"), std::string::npos)
        << e.what();
  }
}

TEST(LoadVrml, SeveralThreadsLoadAtOnce) {
  const auto file =
      write_text("threads.wrl", "#VRML V2.0 utf8\nShape { geometry Sphere { } }\nShape { geometry " +
                                    cube_face_set() + " }\n");
  std::vector<std::size_t> counts(4, 0);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    threads.emplace_back([&, i] { counts[i] = load_model(file).triangle_count(); });
  }
  for (std::thread& t : threads) t.join();
  for (std::size_t c : counts) EXPECT_EQ(c, 402u);
}

}  // namespace
}  // namespace palpate
