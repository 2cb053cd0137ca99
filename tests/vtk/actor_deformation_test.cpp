// palpate's deformation in a VTK actor, rendered by VTK itself (offscreen, under Xvfb: Debian's VTK
// is built for X): against the same actor drawn undeformed, and against VTK drawing palpate's CPU
// reference of the dented mesh (displaced positions, exact normals of the deformed triangles). With
// the actor turned and moved, and far from the origin where VTK shifts and scales its vertex buffer.
#include "palpate/vtk/actor_deformation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "palpate/core/deform.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "picture_comparison.hpp"

namespace palpate::vtk {
namespace {

constexpr int size = 400;

// What VTK applications hang on their actors: colours per point (scalars) and a texture.
struct Decoration {
  bool scalar_colours = false;
  bool texture = false;
  const Mesh* rest = nullptr;  // colours and texture coordinates follow its positions, not the dented ones
};

vtkNew<vtkPolyData> poly_data(const Mesh& mesh, bool normals = true, Decoration decoration = {}) {
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> normal_array;
  normal_array->SetNumberOfComponents(3);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    points->InsertNextPoint(mesh.positions_mm[v].x, mesh.positions_mm[v].y, mesh.positions_mm[v].z);
    normal_array->InsertNextTuple3(mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z);
  }
  vtkNew<vtkCellArray> triangles;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const vtkIdType ids[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    triangles->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(triangles);
  if (normals) poly->GetPointData()->SetNormals(normal_array);
  if (decoration.scalar_colours) {  // bands of colour by height
    vtkNew<vtkUnsignedCharArray> colours;
    colours->SetNumberOfComponents(3);
    for (const glm::vec3& p : decoration.rest->positions_mm)
      colours->InsertNextTuple3(128 + 100 * std::sin(p.z * 0.2f), 200, 128 + 100 * std::cos(p.z * 0.1f));
    poly->GetPointData()->SetScalars(colours);
  }
  if (decoration.texture) {  // longitude and height as texture coordinates
    vtkNew<vtkFloatArray> coordinates;
    coordinates->SetNumberOfComponents(2);
    for (const glm::vec3& p : decoration.rest->positions_mm)
      coordinates->InsertNextTuple2(std::atan2(p.y, p.x) * 0.5f, p.z * 0.02f);
    poly->GetPointData()->SetTCoords(coordinates);
  }
  return poly;
}

// A checkerboard of 8 by 8 texels, repeated.
vtkNew<vtkTexture> checker_texture() {
  vtkNew<vtkImageData> image;
  image->SetDimensions(8, 8, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) image->SetScalarComponentFromFloat(x, y, 0, c, (x + y) % 2 ? 255 : 140);
  vtkNew<vtkTexture> texture;
  texture->SetInputData(image);
  texture->RepeatOn();
  return texture;
}

struct Picture {
  std::vector<unsigned char> rgb;
  int at(int x, int y, int c) const { return rgb[3 * std::size_t(y * size + x) + std::size_t(c)]; }
};

// One window, one renderer, the actor palpate deforms and, decorated, a second actor it leaves alone:
// what a VTK application has.
struct Scene {
  vtkNew<vtkRenderWindow> window;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkPolyDataMapper> mapper, other_mapper;
  vtkNew<vtkActor> actor, other_actor;

  Scene(const Mesh& mesh, const glm::mat4& actor_matrix, glm::vec3 look_at, glm::vec3 eye,
        Decoration decoration = {}) {
    mapper->SetInputData(poly_data(mesh, true, decoration));
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.9, 0.72, 0.62);
    if (decoration.texture) actor->SetTexture(checker_texture());
    if (decoration.scalar_colours || decoration.texture) {
      const Mesh other = make_sphere(20.0f, 2000);
      other_mapper->SetInputData(
          poly_data(other, true, {decoration.scalar_colours, decoration.texture, &other}));
      other_actor->SetMapper(other_mapper);
      other_actor->SetPosition(look_at.x - 60.0, look_at.y - 40.0, look_at.z - 30.0);
      renderer->AddActor(other_actor);
    }
    vtkNew<vtkMatrix4x4> matrix;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) matrix->SetElement(r, c, actor_matrix[c][r]);
    actor->SetUserMatrix(matrix);
    renderer->AddActor(actor);
    renderer->SetBackground(0.1, 0.1, 0.12);
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetPosition(eye.x, eye.y, eye.z);
    camera->SetFocalPoint(look_at.x, look_at.y, look_at.z);
    camera->SetViewUp(0, 0, 1);
    camera->SetViewAngle(40);
    renderer->ResetCameraClippingRange();
    window->SetOffScreenRendering(1);
    window->SetMultiSamples(0);
    window->SetSize(size, size);
    window->AddRenderer(renderer);
  }
  Picture render() {
    renderer->ResetCameraClippingRange();
    window->Render();
    vtkNew<vtkUnsignedCharArray> pixels;
    window->GetPixelData(0, 0, size - 1, size - 1, 1, pixels);
    Picture picture;
    picture.rgb.assign(pixels->GetPointer(0), pixels->GetPointer(0) + 3 * size * size);
    return picture;
  }
};

test::PictureComparison compare(const Picture& a, const Picture& b, glm::vec2 centre_px, float reach_px) {
  return test::compare_pictures(a.rgb, b.rgb, size, size, 3, centre_px, reach_px);
}

// Where a world point lands in the picture (GetPixelData's rows go up from the bottom).
glm::vec2 pixel_of(vtkRenderer* renderer, glm::vec3 world) {
  renderer->SetWorldPoint(world.x, world.y, world.z, 1.0);
  renderer->WorldToDisplay();
  double display[3];
  renderer->GetDisplayPoint(display);
  return {float(display[0]), float(display[1])};
}

void expect_dent_like_the_cpu_reference(const glm::mat4& actor_matrix, glm::vec3 centre,
                                        Decoration decoration = {}) {
  const Mesh sphere = make_sphere(50.0f, 40000);
  const glm::vec3 eye = centre + glm::vec3(0, -190, 50);
  // The contact on the sphere's side facing the camera, in world coordinates.
  const glm::vec3 contact =
      glm::vec3(actor_matrix * glm::vec4(glm::normalize(glm::vec3(0.3f, -1.0f, 0.3f)) * 50.0f, 1.0f));
  const Dent dent{contact, 6.0f, 8.0f};
  decoration.rest = &sphere;

  Scene plain(sphere, actor_matrix, centre, eye, decoration);
  const Picture undeformed = plain.render();
  Scene dented(sphere, actor_matrix, centre, eye, decoration);
  ActorDeformation deformation(dented.actor, dented.renderer);
  EXPECT_EQ(deformation.set({&dent, 1}), 0);
  const Picture deformed = dented.render();

  Mesh reference;  // world coordinates: drawn with an identity actor matrix
  deform_mesh(sphere, actor_matrix, {&dent, 1}, reference);
  Scene cpu(reference, glm::mat4(1.0f), centre, eye, decoration);
  const Picture expected = cpu.render();

  const glm::vec2 centre_px = pixel_of(plain.renderer, contact);
  float reach_px = 0.0f;
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    reach_px = std::max(
        reach_px, glm::distance(pixel_of(plain.renderer, contact + axis * 4.0f * dent.sigma_mm), centre_px));
  const test::PictureComparison against_plain =
      compare(undeformed, deformed, centre_px, reach_px * 1.1f + 3.0f);
  const test::PictureComparison against_cpu = compare(expected, deformed, centre_px, reach_px * 1.1f + 3.0f);
  std::printf("dent %d px (%d beyond its reach); against the CPU reference: mean %.3f, worst %d (of 765)\n",
              against_plain.changed_near, against_plain.changed_far, against_cpu.mean, against_cpu.worst);
  EXPECT_GT(against_plain.changed_near, 1000) << "no dent";
  EXPECT_EQ(against_plain.changed_far, 0) << "changed beyond the dent's reach";
  EXPECT_LT(against_cpu.mean, 0.6) << "unlike the CPU reference";
  EXPECT_LE(against_cpu.worst, 36) << "unlike the CPU reference";  // measured 12 and 17
}

TEST(VtkActorDeformation, DentsLikeTheCpuReferenceAndNowhereElse) {
  expect_dent_like_the_cpu_reference(glm::mat4(1.0f), glm::vec3(0.0f));
}

TEST(VtkActorDeformation, FollowsTheActorsMatrixAndVtksShiftedAndScaledBuffers) {
  // Far from the origin VTK shifts and scales the vertex buffer (vertexMC is not in model units).
  glm::mat4 matrix = glm::translate(glm::mat4(1.0f), glm::vec3(1500, -2500, 800));
  matrix = glm::rotate(matrix, 0.7f, glm::normalize(glm::vec3(1, 1, 0.3f)));
  expect_dent_like_the_cpu_reference(matrix, glm::vec3(1500, -2500, 800));
}

TEST(VtkActorDeformation, KeepsScalarColoursTexturesAndOtherActors) {
  expect_dent_like_the_cpu_reference(glm::mat4(1.0f), glm::vec3(0.0f), {.scalar_colours = true});
  expect_dent_like_the_cpu_reference(glm::mat4(1.0f), glm::vec3(0.0f), {.texture = true});
}

TEST(VtkActorDeformation, RemovedItLeavesTheActorAsItWas) {
  const Mesh sphere = make_sphere(50.0f, 5000);
  Scene scene(sphere, glm::mat4(1.0f), glm::vec3(0), glm::vec3(0, -190, 50));
  const Picture before = scene.render();
  {
    ActorDeformation deformation(scene.actor, scene.renderer);
    const Dent dent{{0, -50, 0}, 6.0f, 8.0f};
    deformation.set({&dent, 1});
    EXPECT_NE(scene.render().rgb, before.rgb);
  }
  EXPECT_EQ(scene.render().rgb, before.rgb);
}

TEST(VtkActorDeformation, AnActorItCannotDeformIsAClearError) {
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkActor> no_mapper;
  EXPECT_THAT([&] { ActorDeformation d(no_mapper, renderer); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("the actor's mapper is not set")));
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(poly_data(make_sphere(10.0f, 500), false));
  vtkNew<vtkActor> no_normals;
  no_normals->SetMapper(mapper);
  EXPECT_THAT(
      [&] { ActorDeformation d(no_normals, renderer); },
      testing::ThrowsMessage<Error>(testing::HasSubstr("no point normals (add a vtkPolyDataNormals")));
}

}  // namespace
}  // namespace palpate::vtk
