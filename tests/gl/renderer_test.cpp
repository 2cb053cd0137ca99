// The renderer on llvmpipe: its per-fragment normals against the true normals of the CPU-deformed
// mesh, p = 0 against the undeformed image, which dents deform which object, and the host's GL state.
#include "palpate/gl/renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <vector>

#include "gl_test_context.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/core/surface_patch.hpp"
#include "palpate/gl/deform_glsl.hpp"
#include "palpate/gl/framebuffer.hpp"
#include "palpate/gl/shader_program.hpp"
#include "palpate/testing/test_shapes.hpp"

namespace palpate::gl {
namespace {

constexpr int size = 512;

Scene scene_of(Mesh mesh, float sigma_mm = 5.0f, const glm::mat4& transform = glm::mat4(1.0f),
               Falloff falloff = Falloff::euclidean) {
  Scene scene;
  SceneObject object;
  object.name = "test mesh";
  object.mesh = std::move(mesh);
  object.transform = transform;
  object.material.sigma_mm = sigma_mm;
  object.material.falloff = falloff;
  scene.objects.push_back(std::move(object));
  return scene;
}

struct Camera {
  glm::mat4 view, projection;
};

Camera looking_at(glm::vec3 eye, glm::vec3 target) {
  return {glm::lookAt(eye, target, glm::vec3(0, 0, 1)),
          glm::perspective(glm::radians(40.0f), 1.0f, 5.0f, 1000.0f)};
}

// Renders `scene` with `dents` into a fresh target and returns its pixels (RGBA, float or 8-bit).
template <class Pixel>
std::vector<Pixel> render(const Scene& scene, const Camera& camera, std::span<const ObjectDent> dents,
                          DrawParams options) {
  const Framebuffer target(
      {size, size, std::is_same_v<Pixel, float> ? ColorFormat::rgba32f : ColorFormat::rgba8});
  target.bind();
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  Renderer renderer;
  renderer.upload(scene);
  renderer.draw(camera.view, camera.projection, dents, options);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  if constexpr (std::is_same_v<Pixel, float>) {
    return target.read_rgba_float();
  } else {
    return target.read_rgba8();
  }
}

DrawParams normals_options(Deformation deformation) {
  DrawParams options;
  options.deformation = deformation;
  options.shading = Shading::normals;
  return options;
}

float angle_deg(glm::vec3 a, glm::vec3 b) {
  return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

struct AngleStats {
  std::size_t pixels = 0;
  float mean = 0.0f, p99 = 0.0f, max = 0.0f;
};

AngleStats stats(std::vector<float> angles) {
  AngleStats s;
  s.pixels = angles.size();
  if (angles.empty()) return s;
  std::sort(angles.begin(), angles.end());
  for (float a : angles) s.mean += a / static_cast<float>(angles.size());
  s.p99 = angles[angles.size() * 99 / 100];
  s.max = angles.back();
  return s;
}

// Largest mean and p99 angle error allowed, degrees: about three times what was measured.
struct Tolerance {
  float mean_deg, p99_deg;
};

// The per-fragment normals of the GPU path against the true ones: the CPU-deformed mesh (deform_mesh,
// exact area-weighted normals of the deformed triangles, in world space) drawn undeformed, its vertex
// normals interpolated. Over all covered pixels, and over those inside the dent alone (where the
// reference leans more than 1 degree off the undeformed normal). The object stands at `transform`.
// With the geodesic falloff the reference reads the surface samples of a SurfacePatch of its own.
void expect_true_normals(const Mesh& mesh, const Dent& dent, const Camera& camera, Tolerance all_pixels,
                         Tolerance dent_pixels, const glm::mat4& transform = glm::mat4(1.0f),
                         Falloff falloff = Falloff::euclidean) {
  const Scene original = scene_of(mesh, dent.sigma_mm, transform, falloff);
  Mesh deformed;
  if (falloff == Falloff::geodesic) {
    SurfacePatch patch(mesh);
    Dent along = dent_with_slope_limit(dent, surface_dent_max_slope);  // as the renderer widens it
    patch.compute(-1, glm::vec3(glm::inverse(transform) * glm::vec4(dent.center_mm, 1.0f)),
                  dent_cutoff_sigmas * along.sigma_mm);
    along.along_surface = true;
    along.normal = glm::mat3(transform) * patch.contact_normal();  // as the renderer pushes it
    deform_mesh(mesh, transform, {&along, 1}, deformed, patch.samples());
  } else {
    deform_mesh(mesh, transform, {&dent, 1}, deformed);
  }
  const Scene reference_scene = scene_of(deformed, dent.sigma_mm);
  const ObjectDent dents[] = {{0, dent}};

  const auto reference = render<float>(reference_scene, camera, {}, normals_options(Deformation::none));
  const auto undeformed = render<float>(original, camera, {}, normals_options(Deformation::none));
  const auto gpu = render<float>(original, camera, dents, normals_options(Deformation::gpu));
  DrawParams every_triangle = normals_options(Deformation::gpu);
  every_triangle.skip_unreached = false;
  EXPECT_EQ(gpu, render<float>(original, camera, dents, every_triangle))
      << "drawing unreached triangles with the plain shader changed the image";

  std::vector<float> all, in_dent;
  float deepest_lean = 0.0f;
  for (std::size_t i = 0; i < gpu.size(); i += 4) {
    if (gpu[i + 3] != 1.0f || reference[i + 3] != 1.0f) continue;
    const glm::vec3 g(gpu[i], gpu[i + 1], gpu[i + 2]), r(reference[i], reference[i + 1], reference[i + 2]);
    const float error = angle_deg(g, r);
    all.push_back(error);
    if (undeformed[i + 3] == 1.0f) {
      const float lean = angle_deg(r, glm::vec3(undeformed[i], undeformed[i + 1], undeformed[i + 2]));
      deepest_lean = std::max(deepest_lean, lean);
      if (lean > 1.0f) in_dent.push_back(error);
    }
  }
  const AngleStats overall = stats(all), dent_only = stats(in_dent);
  EXPECT_GT(overall.pixels, 20000u);
  EXPECT_GT(dent_only.pixels, 2000u) << "the dent covers too few pixels to judge";
  EXPECT_GT(deepest_lean, 15.0f) << "the dent hardly tilts the surface: the test could not fail";
  EXPECT_LE(overall.mean, all_pixels.mean_deg);
  EXPECT_LE(overall.p99, all_pixels.p99_deg);
  EXPECT_LE(dent_only.mean, dent_pixels.mean_deg);
  EXPECT_LE(dent_only.p99, dent_pixels.p99_deg);
  std::printf(
      "normal error, all %zu px: mean %.3f p99 %.3f max %.2f deg; in the dent %zu px: mean %.3f p99 %.3f "
      "max %.2f deg (the dent leans up to %.1f deg)\n",
      overall.pixels, overall.mean, overall.p99, overall.max, dent_only.pixels, dent_only.mean, dent_only.p99,
      dent_only.max, deepest_lean);
}

TEST(RendererNormals, FinePlaneMatchesTheTrueNormals) {
  test::gl_context();
  const Mesh plane = make_grid(80.0f, 240);  // 0.33 mm cells
  // Measured: mean 0.008, p99 0.089 degrees; in the dent 0.021, 0.083.
  expect_true_normals(plane, Dent{{3.0f, 2.0f, 0.0f}, 3.0f, 5.0f},
                      looking_at({0.0f, -45.0f, 50.0f}, {0, 0, 0}), {0.025f, 0.27f}, {0.065f, 0.25f});
}

// The same plane turned 35 degrees about (1, 2, 0.5) and moved: the renderer must carry the object's
// rotation into the positions and the normals. With either falloff (measured p99 0.080 and 0.082
// degrees straight; 0.102 and 0.107 along the surface).
void expect_true_normals_on_the_rotated_plane(Falloff falloff, Tolerance dent_pixels) {
  test::gl_context();
  const Mesh plane = make_grid(80.0f, 240);
  const glm::mat4 transform = glm::rotate(glm::translate(glm::mat4(1.0f), {4.0f, -3.0f, 2.0f}),
                                          glm::radians(35.0f), glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  const glm::vec3 contact = glm::vec3(transform * glm::vec4(3.0f, 2.0f, 0.0f, 1.0f));
  expect_true_normals(plane, Dent{contact, 3.0f, 5.0f},
                      looking_at({0.0f, -60.0f, 60.0f}, {4.0f, -3.0f, 2.0f}), {0.025f, 0.27f}, dent_pixels,
                      transform, falloff);
}

TEST(RendererNormals, RotatedPlaneMatchesTheTrueNormals) {
  expect_true_normals_on_the_rotated_plane(Falloff::euclidean, {0.065f, 0.25f});
}

TEST(RendererNormals, AlongTheSurfaceTheRotatedPlaneMatchesTheTrueNormals) {
  expect_true_normals_on_the_rotated_plane(Falloff::geodesic, {0.065f, 0.3f});
}

// Along the surface on the sphere every vertex is pushed against the contact triangle's normal, not its
// own: the shading normals must follow that surface (N + (N x grad G) x n), not the paper's. The press
// is deep for its sigma (slope 0.91): the renderer widens it to slope 0.75, as the reference does.
TEST(RendererNormals, AlongTheSurfaceTheFineSphereMatchesTheTrueNormals) {
  test::gl_context();
  const Mesh sphere = make_sphere(40.0f, 80000);
  const glm::vec3 contact = glm::normalize(glm::vec3(0.3f, -1.0f, 0.4f)) * 40.0f;
  // Measured: mean 0.029, p99 0.302 degrees; in the dent 0.097, 0.418.
  expect_true_normals(sphere, Dent{contact, 6.0f, 4.0f}, looking_at({20.0f, -130.0f, 60.0f}, {0, 0, 0}),
                      {0.09f, 1.0f}, {0.3f, 1.4f}, glm::mat4(1.0f), Falloff::geodesic);
}

TEST(RendererNormals, FineSphereMatchesTheTrueNormals) {
  test::gl_context();
  const Mesh sphere = make_sphere(40.0f, 80000);
  const glm::vec3 contact = glm::normalize(glm::vec3(0.3f, -1.0f, 0.4f)) * 40.0f;
  // Measured: mean 0.094, p99 1.363 degrees; in the dent 0.284, 1.427 (the sphere's facets: the
  // interpolated reference normals and the per-fragment ones part at the flat triangles' edges).
  expect_true_normals(sphere, Dent{contact, 4.0f, 6.0f}, looking_at({20.0f, -130.0f, 60.0f}, {0, 0, 0}),
                      {0.3f, 4.0f}, {0.9f, 4.3f});
}

struct Bumpy : ::testing::Test {
  Scene scene = scene_of(make_bumpy_sphere(40.0f, 2.5f, 40000), 6.0f);
  Camera camera = looking_at({0.0f, -140.0f, 40.0f}, {0, 0, 0});
  glm::vec3 contact = glm::normalize(glm::vec3(0.1f, -1.0f, 0.3f)) * 41.0f;

  void SetUp() override {
    test::gl_context();
    scene.objects[0].mesh.colors.resize(scene.objects[0].mesh.vertex_count());
    for (std::size_t i = 0; i < scene.objects[0].mesh.vertex_count(); ++i) {
      scene.objects[0].mesh.colors[i] = glm::abs(glm::normalize(scene.objects[0].mesh.positions_mm[i]));
    }
  }
};

TEST_F(Bumpy, ZeroDepthGivesTheUndeformedImageBitForBit) {
  DrawParams plain;
  plain.deformation = Deformation::none;
  const auto undeformed = render<std::uint8_t>(scene, camera, {}, plain);
  const ObjectDent flat[] = {{0, {contact, 0.0f, 6.0f}}};
  for (bool skip_unreached : {true, false}) {
    DrawParams options;
    options.skip_unreached = skip_unreached;
    EXPECT_EQ(render<std::uint8_t>(scene, camera, flat, options), undeformed)
        << "skip_unreached " << skip_unreached;
  }
  const ObjectDent dented[] = {{0, {contact, 4.0f, 6.0f}}};
  EXPECT_NE(render<std::uint8_t>(scene, camera, dented, {}), undeformed);
}

// On a smooth sphere: over the bumps of the bumpy one the paper's rotated normal and the true normal
// part more (the rotation ignores how the undeformed normal turns within the dent).
TEST_F(Bumpy, CpuNaiveAndGpuDrawTheSameDentOnASmoothSphere) {
  scene.objects[0].mesh = make_sphere(40.0f, 40000);
  // The CPU-naive path recomputes every vertex normal from the triangles: start from those normals so
  // that the two paths differ by how they treat the dent only.
  compute_vertex_normals(scene.objects[0].mesh);
  const ObjectDent dents[] = {{0, {contact, 4.0f, 6.0f}}};
  DrawParams naive, none;
  naive.deformation = Deformation::cpu_naive;
  none.deformation = Deformation::none;
  const auto gpu = render<std::uint8_t>(scene, camera, dents, {});
  const auto cpu = render<std::uint8_t>(scene, camera, dents, naive);
  const auto flat = render<std::uint8_t>(scene, camera, {}, none);
  // Pixels that differ by more than a few levels (rounding of normals summed in another order aside).
  const auto differing = [](const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < a.size(); i += 4) {
      int largest = 0;
      for (std::size_t c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(int(a[i + c]) - int(b[i + c])));
      count += largest > 4;
    }
    return count;
  };
  const std::size_t dent_pixels = differing(gpu, flat), disagreeing = differing(gpu, cpu);
  std::printf("the dent changes %zu pixels; the GPU and CPU-naive paths differ on %zu\n", dent_pixels,
              disagreeing);
  EXPECT_GT(dent_pixels, 1000u);
  EXPECT_LT(disagreeing, dent_pixels / 10);
}

TEST(RendererDents, AContactDentsOnlyTheObjectItTouchesWithThatObjectsSigma) {
  test::gl_context();
  Scene scene;
  for (int i = 0; i < 2; ++i) {
    SceneObject object;
    object.name = i == 0 ? "left" : "right";
    object.mesh = make_sphere(30.0f, 20000);
    object.transform = glm::translate(glm::mat4(1.0f), glm::vec3(i == 0 ? -40.0f : 40.0f, 0.0f, 0.0f));
    object.material.sigma_mm = i == 0 ? 3.0f : 8.0f;
    scene.objects.push_back(object);
  }
  const Camera camera = looking_at({0.0f, -200.0f, 0.0f}, {0, 0, 0});
  Contact contact;
  contact.object = 1;
  contact.point_mm = {40.0f, -30.0f, 0.0f};
  contact.hip_mm = {40.0f, -26.0f, 0.0f};
  contact.depth_mm = 4.0f;

  const Framebuffer target({size, size});
  Renderer renderer;
  renderer.upload(scene);
  DrawParams options;
  options.draw_probe = false;
  const auto frame = [&](auto&& draw) {
    target.bind();
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw();
    return target.read_rgba8();
  };
  DrawResult result;
  const auto by_contact = frame([&] {
    result = renderer.draw(camera.view, camera.projection, {&contact, 1}, options);
  });
  EXPECT_EQ(result.deformed_objects, 1);
  EXPECT_EQ(result.dropped_dents, 0);
  const ObjectDent explicit_dent[] = {{1, {contact.point_mm, 4.0f, 8.0f}}};
  EXPECT_EQ(by_contact,
            frame([&] { renderer.draw(camera.view, camera.projection, explicit_dent, options); }));
  const auto undeformed =
      frame([&] { renderer.draw(camera.view, camera.projection, std::span<const ObjectDent>(), options); });

  // The left object (left half of the image) is untouched, the right one dented.
  std::size_t left_changed = 0, right_changed = 0;
  for (std::size_t i = 0; i < by_contact.size(); i += 4) {
    const bool left = (i / 4) % size < size / 2;
    const bool changed = !std::equal(by_contact.begin() + long(i), by_contact.begin() + long(i) + 4,
                                     undeformed.begin() + long(i));
    (left ? left_changed : right_changed) += changed;
  }
  EXPECT_EQ(left_changed, 0u);
  EXPECT_GT(right_changed, 500u);

  // The same dent given to the left object explicitly changes the left half.
  const ObjectDent left_dent[] = {{0, {{-40.0f, -30.0f, 0.0f}, 4.0f, 8.0f}}};
  EXPECT_NE(undeformed, frame([&] { renderer.draw(camera.view, camera.projection, left_dent, options); }));
}

// A wall's corner may give way further from the contact than the dent's 4 sigma in a straight line (up to
// SurfacePatch::wall_reach_edges of the mesh's longest edges further): the triangles around it must be
// drawn by the deforming shader too, not left at rest among the plain ones. A sheet 0.5 mm under another,
// both of 1 mm cells, and in the lower one a sliver from under the press to a corner 21 mm away: pressed
// 3 mm from above, the sliver gives way along its length, and its far corner pokes out of the lower sheet.
// Seen edge-on from beside that corner.
TEST(RendererFalloff, AWallCornerThatGivesWayBeyondFourSigmaIsDrawnWhereItMoved) {
  test::gl_context();
  Mesh sheets;
  testing::add_sheet(sheets, 0.25f, 60, true);
  const std::uint32_t first = std::uint32_t(sheets.vertex_count());  // the lower sheet's first vertex
  testing::add_sheet(sheets, -0.25f, 60, false);
  const auto vertex_at = [&](float x, float y) {  // the lower sheet's vertices lie on whole millimetres
    return first + std::uint32_t(std::lround((y + 30.0f) * 61.0f + (x + 30.0f)));
  };
  const glm::vec3 far_corner(3.0f, -17.0f, -0.25f);
  ASSERT_LT(glm::distance(sheets.positions_mm[vertex_at(far_corner.x, far_corner.y)], far_corner), 1e-4f);
  sheets.indices.insert(
      sheets.indices.end(),  // facing -z, as the lower sheet does
      {vertex_at(3.0f, 3.0f), vertex_at(far_corner.x, far_corner.y), vertex_at(4.0f, 3.0f)});
  const Dent dent{{3.75f, 3.75f, 0.25f}, 3.0f, 3.0f};
  ASSERT_EQ(dent_with_slope_limit(dent, surface_dent_max_slope).sigma_mm, dent.sigma_mm);  // not widened

  SurfacePatch patch(sheets);
  patch.compute(-1, dent.center_mm, SurfacePatch::PushedDent{dent.depth_mm, dent.sigma_mm});
  const glm::vec4 far_sample = patch.samples()[vertex_at(far_corner.x, far_corner.y)];
  const float far_push = dent_gaussian(far_sample.w, dent.depth_mm, dent.sigma_mm);
  ASSERT_GT(glm::distance(far_corner, dent.center_mm), dent_cutoff_sigmas * dent.sigma_mm + 8.0f);
  ASSERT_GT(far_push, 1.0f) << "the far corner should give way";

  const Camera beside{glm::lookAt(far_corner + glm::vec3(30.0f, 0.0f, -1.25f),
                                  far_corner - glm::vec3(0, 0, 1.25f), {0, 0, 1}),
                      glm::perspective(glm::radians(40.0f), 1.0f, 1.0f, 1000.0f)};
  const ObjectDent dents[] = {{0, dent}};
  DrawParams skipping, every_triangle;
  skipping.draw_probe = every_triangle.draw_probe = false;
  every_triangle.skip_unreached = false;
  const Scene geodesic = scene_of(sheets, dent.sigma_mm, glm::mat4(1.0f), Falloff::geodesic);
  const auto drawn = render<std::uint8_t>(geodesic, beside, dents, skipping);
  const auto reference = render<std::uint8_t>(geodesic, beside, dents, every_triangle);
  const auto straight = render<std::uint8_t>(scene_of(sheets, dent.sigma_mm), beside, dents, skipping);
  std::size_t differ = 0, poking_out = 0;
  for (std::size_t i = 0; i < drawn.size(); i += 4) {
    differ += !std::equal(&drawn[i], &drawn[i] + 4, &reference[i]);
    poking_out += !std::equal(&straight[i], &straight[i] + 4, &reference[i]);
  }
  EXPECT_GT(poking_out, 500u) << "the corner that gave way should show";
  EXPECT_EQ(differ, 0u);
  std::printf(
      "a wall corner %.1f mm from the contact (4 sigma: %.0f mm) gave way by %.2f mm: %zu pixels; %zu unlike "
      "every triangle deformed\n",
      glm::distance(far_corner, dent.center_mm), dent_cutoff_sigmas * dent.sigma_mm, far_push, poking_out,
      differ);
}

// The paper's named limit, in pixels: a press on the lower bank of a fold (a sulcus unrolled, 6 mm
// across through the air, 29 mm along the surface) seen from below, where only the upper bank faces
// the camera. The straight-line falloff moves and tilts the upper bank; along the surface it stays
// exactly as it was, through the Contact overload (with its triangle) and the ObjectDent one (without).
TEST(RendererFalloff, AlongTheSurfaceAPressLeavesTheFacingBankOfAFoldAlone) {
  test::gl_context();
  const Mesh fold = testing::make_folded_sheet();
  const Camera below{glm::lookAt(glm::vec3(30.0f, 0.0f, -70.0f), glm::vec3(30.0f, 0.0f, 6.0f), {0, 1, 0}),
                     glm::perspective(glm::radians(40.0f), 1.0f, 5.0f, 1000.0f)};
  Contact press;
  press.object = 0;
  press.point_mm = {30.2f, 0.3f, 0.0f};
  press.hip_mm = press.point_mm - glm::vec3(0.0f, 0.0f, 3.0f);
  press.normal = {0.0f, 0.0f, 1.0f};
  press.depth_mm = 3.0f;
  for (std::uint32_t t = 0; 3 * t < fold.indices.size(); ++t) {  // the triangle under the press
    const glm::vec3 a = fold.positions_mm[fold.indices[3 * t]],
                    b = fold.positions_mm[fold.indices[3 * t + 1]],
                    c = fold.positions_mm[fold.indices[3 * t + 2]];
    const glm::vec3 q = press.point_mm;
    const auto side = [&](glm::vec3 u, glm::vec3 v) {
      return (v.x - u.x) * (q.y - u.y) - (v.y - u.y) * (q.x - u.x);
    };
    if (a.z == 0.0f && b.z == 0.0f && c.z == 0.0f && side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0)
      press.triangle = int(t);
  }
  ASSERT_GE(press.triangle, 0);
  const ObjectDent dent[] = {{0, dent_from_contact(press, 4.0f)}};
  DrawParams options;
  options.draw_probe = false;
  const auto undeformed = render<std::uint8_t>(scene_of(fold, 4.0f), below, {}, options);
  const auto straight = render<std::uint8_t>(scene_of(fold, 4.0f), below, dent, options);
  const Scene geodesic = scene_of(fold, 4.0f, glm::mat4(1.0f), Falloff::geodesic);
  const auto along = render<std::uint8_t>(geodesic, below, dent, options);
  const Framebuffer target({size, size, ColorFormat::rgba8});
  target.bind();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  Renderer renderer;
  renderer.upload(geodesic);
  renderer.draw(below.view, below.projection, {&press, 1}, options);
  const auto along_from_contact = target.read_rgba8();

  std::size_t covered = 0, changed_straight = 0;
  for (std::size_t i = 0; i < undeformed.size(); i += 4) {
    covered += undeformed[i + 3] != 0;
    changed_straight += !std::equal(&undeformed[i], &undeformed[i] + 4, &straight[i]);
  }
  EXPECT_GT(covered, 100000u);
  EXPECT_GT(changed_straight, 3000u) << "the straight line should dent the facing bank";
  EXPECT_EQ(along, undeformed);
  EXPECT_EQ(along_from_contact, undeformed);
  std::printf(
      "fold seen from below: %zu px covered; the press changes %zu px straight, none along the surface\n",
      covered, changed_straight);
}

TEST(RendererDents, DentsPastTheLimitOrForNoObjectAreDroppedAndCounted) {
  test::gl_context();
  const Framebuffer target({64, 64});
  target.bind();
  Renderer renderer;
  renderer.upload(scene_of(make_sphere(30.0f, 2000)));
  std::vector<ObjectDent> dents(max_dents + 1, ObjectDent{0, {{0.0f, -30.0f, 0.0f}, 1.0f, 5.0f}});
  dents.push_back({7, {}});
  dents.push_back({-1, {}});
  const Camera camera = looking_at({0.0f, -100.0f, 0.0f}, {0, 0, 0});
  const DrawResult result = renderer.draw(camera.view, camera.projection, dents);
  EXPECT_EQ(result.dropped_dents, 3);
  EXPECT_EQ(result.deformed_objects, 1);
  Contact nowhere;
  nowhere.object = 3;
  nowhere.depth_mm = 1.0f;
  EXPECT_EQ(renderer.draw(camera.view, camera.projection, {&nowhere, 1}).dropped_dents, 1);
}

// Every piece of GL state a host might have set that the renderer could touch, read back.
std::vector<GLint64> gl_state_snapshot() {
  std::vector<GLint64> s;
  const auto integer = [&](GLenum name, int count = 1) {
    GLint64 values[4] = {};
    glGetInteger64v(name, values);
    s.insert(s.end(), values, values + count);
  };
  const auto indexed = [&](GLenum name, GLuint index) {
    GLint64 value = 0;
    glGetInteger64i_v(name, index, &value);
    s.push_back(value);
  };
  for (GLenum name : {GL_CURRENT_PROGRAM,
                      GL_VERTEX_ARRAY_BINDING,
                      GL_ARRAY_BUFFER_BINDING,
                      GL_ELEMENT_ARRAY_BUFFER_BINDING,
                      GL_UNIFORM_BUFFER_BINDING,
                      GL_DRAW_FRAMEBUFFER_BINDING,
                      GL_READ_FRAMEBUFFER_BINDING,
                      GL_ACTIVE_TEXTURE,
                      GL_TEXTURE_BINDING_2D,
                      GL_DEPTH_FUNC,
                      GL_DEPTH_WRITEMASK,
                      GL_CULL_FACE_MODE,
                      GL_FRONT_FACE,
                      GL_BLEND_SRC_RGB,
                      GL_BLEND_DST_RGB,
                      GL_BLEND_EQUATION_RGB,
                      GL_PROGRAM_PIPELINE_BINDING,
                      GL_TRANSFORM_FEEDBACK_BINDING,
                      GL_RENDERBUFFER_BINDING,
                      GL_PIXEL_PACK_BUFFER_BINDING}) {
    integer(name);
  }
  integer(GL_VIEWPORT, 4);
  integer(GL_SCISSOR_BOX, 4);
  integer(GL_COLOR_WRITEMASK, 4);
  integer(GL_POLYGON_MODE, 2);
  for (GLuint binding = 0; binding < 8; ++binding) {
    indexed(GL_UNIFORM_BUFFER_BINDING, binding);
    indexed(GL_UNIFORM_BUFFER_START, binding);
    indexed(GL_UNIFORM_BUFFER_SIZE, binding);
  }
  for (GLenum cap : {GL_DEPTH_TEST, GL_CULL_FACE, GL_BLEND, GL_SCISSOR_TEST, GL_STENCIL_TEST, GL_MULTISAMPLE,
                     GL_PRIMITIVE_RESTART, GL_RASTERIZER_DISCARD, GL_POLYGON_OFFSET_FILL}) {
    s.push_back(glIsEnabled(cap));
  }
  return s;
}

TEST(RendererState, LeavesTheHostsGlStateAsItFoundItAndIgnoresIt) {
  test::gl_context();
  // A second object inside the first, so that the occlusion query runs (and masks colour) too.
  Scene scene = scene_of(make_bumpy_sphere(40.0f, 2.0f, 20000), 6.0f);
  SceneObject inner;
  inner.name = "inner";
  inner.mesh = make_sphere(20.0f, 2000);
  scene.objects.push_back(inner);
  const Camera camera = looking_at({0.0f, -140.0f, 40.0f}, {0, 0, 0});
  Contact contact;
  contact.object = 0;
  contact.point_mm = glm::normalize(glm::vec3(0.1f, -1.0f, 0.3f)) * 40.0f;
  contact.hip_mm = contact.point_mm * 0.95f;
  contact.depth_mm = 3.0f;
  const Framebuffer target({size, size});
  Renderer renderer;
  renderer.upload(scene);
  DrawParams options;
  options.draw_contact_points = true;
  options.read_occlusion_results = true;
  const auto frame = [&] {
    const DrawResult result = renderer.draw(camera.view, camera.projection, {&contact, 1}, options);
    EXPECT_EQ(result.occlusion_tested, 1);
    EXPECT_EQ(result.occlusion_culled, 1);
    options.deformation = Deformation::cpu_naive;
    renderer.draw(camera.view, camera.projection, {&contact, 1}, options);
    options.deformation = Deformation::gpu;
  };

  target.bind();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  frame();
  const auto expected = target.read_rgba8();

  // A host with its own program, arrays, buffers and unusual fixed-function state.
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const ShaderProgram host_program("host", "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n",
                                   "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  GLuint vao = 0, buffers[3] = {}, texture = 0;
  glGenVertexArrays(1, &vao);
  glGenBuffers(3, buffers);
  glGenTextures(1, &texture);
  glUseProgram(host_program.id());
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
  glBindBuffer(GL_UNIFORM_BUFFER, buffers[1]);
  glBufferData(GL_UNIFORM_BUFFER, 1024, nullptr, GL_STATIC_DRAW);
  glBindBufferRange(GL_UNIFORM_BUFFER, Renderer::dent_binding, buffers[1], 256, 512);
  glBindBuffer(GL_UNIFORM_BUFFER, buffers[2]);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, texture);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_FALSE);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glFrontFace(GL_CW);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  glScissor(3, 4, 50, 60);
  glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
  const std::vector<GLint64> before = gl_state_snapshot();
  frame();
  EXPECT_EQ(gl_state_snapshot(), before);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

  // The host's state does not leak into the renderer's drawing either.
  glDisable(GL_BLEND);
  EXPECT_EQ(target.read_rgba8(), expected);

  glUseProgram(0);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  glActiveTexture(GL_TEXTURE0);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glDeleteTextures(1, &texture);
  glDeleteBuffers(3, buffers);
  glDeleteVertexArrays(1, &vao);
}

}  // namespace
}  // namespace palpate::gl

namespace palpate::gl {
namespace {

// Inside a host's own render pass: into the host's framebuffer, tested against the host's depth (here
// the left half already holds something at the near plane), and writing depth for what the host draws
// after it.
TEST(RendererTarget, DrawsIntoTheHostsFramebufferAgainstTheHostsDepthAndWritesDepth) {
  test::gl_context();
  Renderer renderer;
  renderer.upload(scene_of(make_sphere(20.0f, 2000)));
  const Camera camera = looking_at({0.0f, -100.0f, 0.0f}, {0, 0, 0});
  constexpr int side = 64;
  GLuint framebuffer = 0, renderbuffers[2];
  glCreateFramebuffers(1, &framebuffer);
  glCreateRenderbuffers(2, renderbuffers);
  glNamedRenderbufferStorage(renderbuffers[0], GL_RGBA8, side, side);
  glNamedRenderbufferStorage(renderbuffers[1], GL_DEPTH_COMPONENT24, side, side);
  glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers[0]);
  glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers[1]);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, side, side);
  glClearColor(0, 0, 0, 0);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);  // the host's near occluder over the left half
  glScissor(0, 0, side / 2, side);
  glClearDepth(0.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  glClearDepth(1.0);

  const DrawResult result = renderer.draw(camera.view, camera.projection, std::span<const ObjectDent>{});
  EXPECT_FALSE(result.drew_nothing());
  EXPECT_FALSE(result.no_depth_buffer);
  std::vector<std::uint8_t> color(side * side * 4);
  std::vector<float> depth(side * side);
  glReadPixels(0, 0, side, side, GL_RGBA, GL_UNSIGNED_BYTE, color.data());
  glReadPixels(0, 0, side, side, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  int left_drawn = 0, right_drawn = 0, right_depth_written = 0;
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const std::size_t i = std::size_t(y) * side + std::size_t(x);
      const bool drawn = color[4 * i + 3] > 0;
      (x < side / 2 ? left_drawn : right_drawn) += drawn;
      right_depth_written += x >= side / 2 && drawn && depth[i] < 1.0f;
    }
  }
  EXPECT_EQ(left_drawn, 0) << "drawn over the host's nearer content";
  EXPECT_GT(right_drawn, 100) << "the sphere did not reach the host's framebuffer";
  EXPECT_EQ(right_depth_written, right_drawn) << "the sphere's pixels did not write depth";
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteRenderbuffers(2, renderbuffers);
}

// Drawn where nothing can show, the renderer says why instead of drawing nothing silently.
TEST(RendererTarget, ReportsAZeroViewportAnIncompleteFramebufferAndAMissingDepthBuffer) {
  test::gl_context();
  Renderer renderer;
  renderer.upload(scene_of(make_sphere(20.0f, 500)));
  const Camera camera = looking_at({0.0f, -100.0f, 0.0f}, {0, 0, 0});
  const Framebuffer target({64, 64});
  target.bind();
  DrawResult result = renderer.draw(camera.view, camera.projection, std::span<const ObjectDent>{});
  EXPECT_FALSE(result.drew_nothing());
  EXPECT_FALSE(result.no_depth_buffer);

  glViewport(0, 0, 0, 64);
  result = renderer.draw(camera.view, camera.projection, std::span<const ObjectDent>{});
  EXPECT_TRUE(result.zero_viewport);
  EXPECT_TRUE(result.drew_nothing());
  glViewport(0, 0, 64, 64);

  // A host framebuffer with a colour attachment only.
  GLuint framebuffer = 0, color = 0;
  glCreateFramebuffers(1, &framebuffer);
  glCreateRenderbuffers(1, &color);
  glNamedRenderbufferStorage(color, GL_RGBA8, 64, 64);
  glNamedFramebufferRenderbuffer(framebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  result = renderer.draw(camera.view, camera.projection, std::span<const ObjectDent>{});
  EXPECT_TRUE(result.no_depth_buffer);
  EXPECT_FALSE(result.drew_nothing());
  // And one with nothing attached at all.
  GLuint empty = 0;
  glCreateFramebuffers(1, &empty);
  glBindFramebuffer(GL_FRAMEBUFFER, empty);
  result = renderer.draw(camera.view, camera.projection, std::span<const ObjectDent>{});
  EXPECT_TRUE(result.incomplete_framebuffer);
  EXPECT_TRUE(result.drew_nothing());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &framebuffer);
  glDeleteFramebuffers(1, &empty);
  glDeleteRenderbuffers(1, &color);
}

}  // namespace
}  // namespace palpate::gl
