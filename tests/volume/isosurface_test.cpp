// Isosurfaces of volumes made here, whose surfaces are known exactly: a sphere and a torus sampled as
// signed distances on anisotropic voxels placed by a rotated and shifted voxel-to-mm matrix. Their
// area, enclosed volume and genus against the analytic ones, in the right millimetre frame.
#include "palpate/volume/isosurface.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "palpate/core/error.hpp"
#include "palpate/core/mesh_topology.hpp"

namespace palpate::volume {
namespace {

constexpr double pi = glm::pi<double>();

// Voxels of 0.8 x 1.0 x 1.3 mm, turned 20 degrees about (1, 2, 3) and moved to (30, -40, 12) mm.
glm::dmat4 tilted_voxels() {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(30.0, -40.0, 12.0));
  m = glm::rotate(m, glm::radians(20.0), glm::normalize(glm::dvec3(1, 2, 3)));
  return glm::scale(m, glm::dvec3(0.8, 1.0, 1.3));
}

// A volume of `size` voxels whose value at each voxel centre is field(position in mm), the voxel grid
// centred on `centre_mm`.
Volume sampled(glm::ivec3 size, glm::dvec3 centre_mm, const std::function<double(glm::dvec3)>& field) {
  Volume volume;
  volume.size = size;
  volume.voxel_to_mm = tilted_voxels();
  // Shift the grid so that its middle voxel lands on the centre.
  const glm::dvec3 middle = glm::dvec3(volume.voxel_to_mm * glm::dvec4(glm::dvec3(size - 1) * 0.5, 1.0));
  volume.voxel_to_mm = glm::translate(glm::dmat4(1.0), centre_mm - middle) * volume.voxel_to_mm;
  volume.source = "synthetic";
  volume.values.reserve(std::size_t(size.x) * std::size_t(size.y) * std::size_t(size.z));
  for (int k = 0; k < size.z; ++k)
    for (int j = 0; j < size.y; ++j)
      for (int i = 0; i < size.x; ++i)
        volume.values.push_back(float(field(glm::dvec3(volume.voxel_to_mm * glm::dvec4(i, j, k, 1.0)))));
  return volume;
}

double area(const Mesh& mesh) {
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a = mesh.positions_mm[mesh.indices[t]], b = mesh.positions_mm[mesh.indices[t + 1]],
                     c = mesh.positions_mm[mesh.indices[t + 2]];
    sum += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return sum;
}

double enclosed_volume(const Mesh& mesh) {  // positive when the triangles face outward
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a = mesh.positions_mm[mesh.indices[t]], b = mesh.positions_mm[mesh.indices[t + 1]],
                     c = mesh.positions_mm[mesh.indices[t + 2]];
    sum += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return sum;
}

const glm::dvec3 centre_mm(12.0, -25.0, 40.0);

Volume sphere_volume(double radius) {
  return sampled({70, 56, 44}, centre_mm, [&](glm::dvec3 p) { return radius - glm::distance(p, centre_mm); });
}

TEST(Isosurface, SphereOnTiltedAnisotropicVoxelsHasTheAnalyticAreaVolumeAndPlace) {
  constexpr double radius = 20.0;
  const Isosurface surface = extract_isosurface(sphere_volume(radius), {.iso = 0.0f});
  const Mesh& mesh = surface.mesh;
  const MeshTopology topology = analyze_topology(mesh);
  EXPECT_TRUE(topology.closed() && topology.manifold() && topology.oriented());
  EXPECT_EQ(topology.genus(), 0);
  const double area_error = area(mesh) / (4.0 * pi * radius * radius) - 1.0;
  const double volume_error = enclosed_volume(mesh) / (4.0 / 3.0 * pi * radius * radius * radius) - 1.0;
  std::printf("sphere: %zu vertices, area %+.3f%%, volume %+.3f%%\n", mesh.vertex_count(), 100 * area_error,
              100 * volume_error);
  EXPECT_LT(std::abs(area_error), 0.01);
  EXPECT_LT(std::abs(volume_error), 0.01);
  double worst = 0.0;  // every vertex on the sphere, in millimetres
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    worst = std::max(worst, std::abs(glm::distance(glm::dvec3(mesh.positions_mm[v]), centre_mm) - radius));
    EXPECT_GT(glm::dot(glm::dvec3(mesh.normals[v]), glm::dvec3(mesh.positions_mm[v]) - centre_mm), 0.0)
        << "normal " << v << " points inward";
  }
  EXPECT_LT(worst, 0.05);
}

TEST(Isosurface, TorusHasGenusOneAndTheAnalyticAreaAndVolume) {
  constexpr double major = 22.0, minor = 7.0;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(0.3, -0.2, 1.0));
  const Volume volume = sampled({80, 64, 40}, centre_mm, [&](glm::dvec3 p) {
    const glm::dvec3 d = p - centre_mm;
    const double along = glm::dot(d, axis);
    const double across = glm::length(d - along * axis);
    return minor - std::hypot(across - major, along);
  });
  const Mesh mesh = extract_isosurface(volume, {.iso = 0.0f}).mesh;
  const MeshTopology topology = analyze_topology(mesh);
  EXPECT_TRUE(topology.closed() && topology.manifold() && topology.oriented());
  EXPECT_EQ(topology.genus(), 1);
  const double area_error = area(mesh) / (4.0 * pi * pi * major * minor) - 1.0;
  const double volume_error = enclosed_volume(mesh) / (2.0 * pi * pi * major * minor * minor) - 1.0;
  std::printf("torus: %zu vertices, area %+.3f%%, volume %+.3f%%\n", mesh.vertex_count(), 100 * area_error,
              100 * volume_error);
  EXPECT_LT(std::abs(area_error), 0.01);
  EXPECT_LT(std::abs(volume_error), 0.01);
}

TEST(Isosurface, DecimationKeepsTheTopologyAndHitsTheVertexCount) {
  const Isosurface surface = extract_isosurface(sphere_volume(20.0), {.iso = 0.0f, .vertices = 2000});
  const MeshTopology topology = analyze_topology(surface.mesh);
  EXPECT_TRUE(topology.closed() && topology.manifold() && topology.oriented());
  EXPECT_EQ(topology.genus(), 0);
  EXPECT_NEAR(double(surface.mesh.vertex_count()), 2000.0, 20.0);
  EXPECT_EQ(surface.stages.back().name, "normals");
  EXPECT_EQ(surface.stages[surface.stages.size() - 2].name, "decimate");
  EXPECT_LT(std::abs(enclosed_volume(surface.mesh) / (4.0 / 3.0 * pi * 8000.0) - 1.0), 0.02);
}

// A ball cut by the volume's border: open unless closed against it; a hollow ball: two surfaces unless
// closed (the inner one is not reachable from outside).
TEST(Isosurface, ClosingSealsTheBorderAndFillsWhatOutsideAirCannotReach) {
  const Volume cut = sampled({40, 40, 40}, centre_mm + glm::dvec3(0, 0, 18),
                             [&](glm::dvec3 p) { return 20.0 - glm::distance(p, centre_mm); });
  EXPECT_FALSE(analyze_topology(extract_isosurface(cut, {.iso = 0.0f}).mesh).closed());
  const MeshTopology sealed = analyze_topology(extract_isosurface(cut, {.iso = 0.0f, .closed = true}).mesh);
  EXPECT_TRUE(sealed.closed() && sealed.manifold());
  EXPECT_EQ(sealed.components, 1u);

  const Volume hollow = sampled({70, 56, 44}, centre_mm, [&](glm::dvec3 p) {
    const double r = glm::distance(p, centre_mm);
    return std::min(20.0 - r, r - 10.0);  // a shell between 10 and 20 mm
  });
  EXPECT_EQ(analyze_topology(extract_isosurface(hollow, {.iso = 0.0f}).mesh).components, 2u);
  const Mesh filled = extract_isosurface(hollow, {.iso = 0.0f, .closed = true}).mesh;
  EXPECT_EQ(analyze_topology(filled).components, 1u);
  EXPECT_LT(std::abs(enclosed_volume(filled) / (4.0 / 3.0 * pi * 8000.0) - 1.0), 0.01);
}

TEST(Isosurface, LargestKeepsTheBiggerOfTwoBalls) {
  const Volume two = sampled({80, 64, 44}, centre_mm, [&](glm::dvec3 p) {
    return std::max(15.0 - glm::distance(p, centre_mm + glm::dvec3(12, 0, 0)),
                    6.0 - glm::distance(p, centre_mm - glm::dvec3(15, 0, 0)));
  });
  // (the grid's tilt puts both inside it)
  EXPECT_EQ(analyze_topology(extract_isosurface(two, {.iso = 0.0f}).mesh).components, 2u);
  const Mesh largest = extract_isosurface(two, {.iso = 0.0f, .largest = true}).mesh;
  EXPECT_EQ(analyze_topology(largest).components, 1u);
  EXPECT_LT(std::abs(enclosed_volume(largest) / (4.0 / 3.0 * pi * 15.0 * 15.0 * 15.0) - 1.0), 0.01);
}

TEST(Isosurface, AThresholdOutsideTheIntensitiesIsAnErrorGivingTheRange) {
  EXPECT_THAT([] { extract_isosurface(sphere_volume(20.0), {.iso = 500.0f}); },
              testing::ThrowsMessage<Error>(testing::AllOf(testing::HasSubstr("synthetic"),
                                                           testing::HasSubstr("threshold 500 is outside"))));
}

}  // namespace
}  // namespace palpate::volume
