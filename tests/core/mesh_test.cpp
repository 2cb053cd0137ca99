// validate_mesh, the check every mesh passes on its way in (loaders, the renderer, the writers): each
// fault named with the vertex or triangle it is in.
#include "palpate/core/mesh.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"

namespace palpate {
namespace {

std::string validation_error(const Mesh& mesh) {
  try {
    validate_mesh(mesh, "test mesh");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ValidateMesh, AcceptsAGoodMesh) {
  EXPECT_EQ(validation_error(make_box(glm::vec3(2.0f))), "");
}

TEST(ValidateMesh, NamesANonFiniteVertex) {
  Mesh box = make_box(glm::vec3(2.0f));
  box.positions_mm[5].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(validation_error(box), "test mesh: vertex 5 has a non-finite coordinate (NaN or Inf)");
  box.positions_mm[5].y = 0.0f;
  box.normals[2].z = std::numeric_limits<float>::infinity();
  EXPECT_EQ(validation_error(box), "test mesh: normal 2 is not finite");
}

TEST(ValidateMesh, RejectsAnIndexOnePastTheLastVertex) {
  Mesh box = make_box(glm::vec3(2.0f));  // 8 vertices
  box.indices[4] = 8;
  EXPECT_EQ(validation_error(box), "test mesh: triangle 1 uses vertex 8 but there are only 8");
  box.indices[4] = 7;
  EXPECT_EQ(validation_error(box), "");
}

TEST(ValidateMesh, RejectsPerVertexArraysOfTheWrongSize) {
  Mesh box = make_box(glm::vec3(2.0f));
  box.directions.assign(7, glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(validation_error(box), "test mesh: 7 directions for 8 positions");
  box.directions.clear();
  box.colors.assign(3, glm::vec3(1.0f));
  EXPECT_EQ(validation_error(box), "test mesh: 3 colors for 8 positions");
}

}  // namespace
}  // namespace palpate
