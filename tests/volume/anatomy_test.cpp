// The real default scene: Colin27's brain and skin from Debian's mricron-data (skipped when the package
// is not installed), its cache, and the fallback to the phantoms.
#include "palpate/volume/anatomy.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <glm/geometric.hpp>

#include "palpate/core/mesh_topology.hpp"
#include "palpate/testing/surface_oracle.hpp"
#include "test_paths.hpp"

namespace palpate::volume {
namespace {

TEST(Colin27, BrainAndSkinAtTableOneSizesClosedManifoldBrainInsideSkinAndCached) {
  const std::optional<Colin27> colin = find_colin27();
  if (!colin) GTEST_SKIP() << "mricron-data is not installed";
  const auto cache = test::scratch_dir("colin27_cache");
  DefaultSceneParams params;
  params.cache_dir = cache;
  const auto cold_start = std::chrono::steady_clock::now();
  const Scene scene = default_scene(params);
  const double cold_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - cold_start).count();
  ASSERT_EQ(scene.objects.size(), 2u);
  const SceneObject &brain = scene.objects[0], &skin = scene.objects[1];
  EXPECT_EQ(brain.name, "brain");
  EXPECT_EQ(skin.name, "skin");
  EXPECT_NEAR(double(brain.mesh.vertex_count()), double(brain_phantom_vertices),
              0.01 * brain_phantom_vertices);
  EXPECT_NEAR(double(skin.mesh.vertex_count()), double(skin_phantom_vertices), 0.01 * skin_phantom_vertices);
  for (const SceneObject* object : {&brain, &skin}) {
    const MeshTopology topology = analyze_topology(object->mesh);
    EXPECT_TRUE(topology.closed() && topology.manifold() && topology.oriented()) << object->name;
    EXPECT_EQ(topology.components, 1u) << object->name;
  }
  EXPECT_EQ(brain.material.sigma_mm, brain_material.sigma_mm);
  EXPECT_EQ(skin.material.sigma_mm, skin_material.sigma_mm);

  // Every 17th brain vertex is inside the skin (the skin's winding number around it, palpate_testing's
  // independent oracle).
  Scene skin_only;
  skin_only.objects.push_back(skin);
  const testing::MeshOracle oracle(skin_only);
  std::size_t sampled = 0, inside = 0;
  for (std::size_t v = 0; v < brain.mesh.vertex_count(); v += 17) {
    ++sampled;
    inside += oracle.inside(glm::dvec3(brain.mesh.positions_mm[v]));
  }
  EXPECT_EQ(inside, sampled);

  // A second start reads the cache: the same meshes, without the pipeline.
  const auto warm_start = std::chrono::steady_clock::now();
  const Scene again = default_scene(params);
  const double warm_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - warm_start).count();
  std::printf(
      "Colin27: brain %zu, skin %zu vertices; %zu of %zu sampled brain vertices inside the skin; "
      "cold %.1f s, cached %.2f s\n",
      brain.mesh.vertex_count(), skin.mesh.vertex_count(), inside, sampled, cold_s, warm_s);
  ASSERT_EQ(again.objects.size(), 2u);
  EXPECT_EQ(again.objects[0].mesh.vertex_count(), brain.mesh.vertex_count());
  EXPECT_EQ(again.objects[1].mesh.triangle_count(), skin.mesh.triangle_count());
  EXPECT_EQ(again.objects[1].source.parent_path(), cache);
}

TEST(DefaultScene, WithoutColin27ItSaysSoInOneLineAndGivesThePhantoms) {
  DefaultSceneParams params;
  params.colin27_folder = test::scratch_dir("no_mricron");
  std::vector<std::string> notes;
  params.on_note = [&](const std::string& note) { notes.push_back(note); };
  const Scene scene = default_scene(params);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("install the Debian package mricron-data"), std::string::npos) << notes[0];
  EXPECT_EQ(notes[0].find('\n'), std::string::npos);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.objects[0].mesh.vertex_count(), brain_phantom_vertices);
}

}  // namespace
}  // namespace palpate::volume
