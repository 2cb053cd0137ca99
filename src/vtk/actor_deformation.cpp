#include "palpate/vtk/actor_deformation.hpp"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkOpenGLCamera.h>
#include <vtkOpenGLPolyDataMapper.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>
#include <vtkShaderProperty.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <glm/mat4x4.hpp>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/gl/deform_glsl.hpp"

namespace palpate::vtk {
namespace {

// VTK 9's templates: `//VTK::Normal::Dec` in both stages (kept by VTK's own replacement, so a
// replacement that keeps it too stays in place), `//VTK::PositionVC::Impl` in the vertex stage (VTK's
// code there consumes the tag: replaced before it), `//VTK::Normal::Impl` in the fragment stage, after
// VTK's normalisation and back-face flip of normalVCVSOutput.
constexpr const char* normal_dec = "//VTK::Normal::Dec";
constexpr const char* position_impl = "//VTK::PositionVC::Impl";
constexpr const char* normal_impl = "//VTK::Normal::Impl";

// Displaced in view coordinates (MCVCMatrix holds the actor's matrix and the buffer's shift and scale);
// gl_Position is VTK's own plus the displacement taken to clip space by the camera's projection
// (palpateVCDC, fed with the dents), so that away from the dents it is VTK's to the bit.
constexpr const char* vertex_position = R"glsl(
  vec4 palpateRest = MCVCMatrix * vertexMC;
  palpateRestVC = palpateRest.xyz;
  vertexVCVSOutput = vec4(palpate_displace(palpateRest.xyz, normalize(normalMatrix * normalMC)), 1.0);
  gl_Position = MCDCMatrix * vertexMC + palpateVCDC * vec4(vertexVCVSOutput.xyz - palpateRest.xyz, 0.0);
)glsl";

constexpr const char* fragment_normal = R"glsl(//VTK::Normal::Impl
  if (palpate_reaches(palpateRestVC)) normalVCVSOutput = palpate_perturb_normal(normalVCVSOutput, palpateRestVC);
)glsl";

glm::mat4 to_glm(vtkMatrix4x4* m) {  // VTK's matrices are row-major
  glm::mat4 out(1.0f);
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) out[column][row] = float(m->GetElement(row, column));
  return out;
}

}  // namespace

struct ActorDeformation::State {
  vtkSmartPointer<vtkActor> actor;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkOpenGLPolyDataMapper> mapper;
  vtkNew<vtkCallbackCommand> feed;
  unsigned long observer = 0;
  int slots = 1;
  Dent dents[max_dents]{};
  int count = 0;

  // Before each draw of the actor: the dents into the active camera's view coordinates.
  void update(vtkShaderProgram& program) {
    const glm::mat4 view = to_glm(renderer->GetActiveCamera()->GetModelViewTransformMatrix());
    Dent in_view[max_dents];
    for (int i = 0; i < count; ++i) in_view[i] = dent_in_space(dents[i], view);
    const gl::DeformBlockData data = gl::make_deform_block_data({in_view, std::size_t(count)});
    program.SetUniform4fv("palpate_dent_center_depth", slots, &data.center_depth[0].x);
    program.SetUniform4fv("palpate_dent_shape", slots, &data.shape[0].x);
    program.SetUniformi("palpate_dent_count", std::min(data.count, slots));
    vtkMatrix4x4 *world_to_view = nullptr, *view_to_clip = nullptr, *world_to_clip = nullptr;
    vtkMatrix3x3* normals = nullptr;
    static_cast<vtkOpenGLCamera*>(renderer->GetActiveCamera())
        ->GetKeyMatrices(renderer, world_to_view, normals, view_to_clip, world_to_clip);
    program.SetUniformMatrix("palpateVCDC", view_to_clip);
  }
};

ActorDeformation::ActorDeformation(vtkActor* actor, vtkRenderer* renderer, int dent_slots)
    : state_(std::make_unique<State>()) {
  if (!actor || !renderer) throw Error("palpate::vtk::ActorDeformation: no actor or no renderer");
  auto* mapper = vtkOpenGLPolyDataMapper::SafeDownCast(actor->GetMapper());
  if (!mapper) {
    throw Error(std::string("palpate::vtk::ActorDeformation: the actor's mapper is ") +
                (actor->GetMapper() ? actor->GetMapper()->GetClassName() : "not set") +
                ", not a vtkOpenGLPolyDataMapper");
  }
  mapper->Update();
  vtkPolyData* input = mapper->GetInput();
  if (!input || !input->GetPointData()->GetNormals()) {
    throw Error(
        "palpate::vtk::ActorDeformation: the mapper's input has no point normals (add a vtkPolyDataNormals "
        "before the mapper)");
  }
  state_->actor = actor;
  state_->renderer = renderer;
  state_->mapper = mapper;
  state_->slots = std::clamp(dent_slots, 1, max_dents);

  // GLSL 1.50, VTK's: the uniform arrays (custom plain uniforms), set by the observer below.
  const std::string snippet = gl::deform_glsl(gl::GlslDialect::uniform_arrays, state_->slots);
  vtkShaderProperty* shaders = actor->GetShaderProperty();
  shaders->AddVertexShaderReplacement(
      normal_dec, true,
      std::string(normal_dec) + "\n" + snippet + "out vec3 palpateRestVC;\nuniform mat4 palpateVCDC;\n",
      false);
  shaders->AddVertexShaderReplacement(position_impl, true, vertex_position, false);
  shaders->AddFragmentShaderReplacement(
      normal_dec, true, std::string(normal_dec) + "\n" + snippet + "in vec3 palpateRestVC;\n", false);
  shaders->AddFragmentShaderReplacement(normal_impl, false, fragment_normal, false);

  state_->feed->SetClientData(state_.get());
  state_->feed->SetCallback([](vtkObject*, unsigned long, void* state, void* program) {
    if (program) static_cast<State*>(state)->update(*static_cast<vtkShaderProgram*>(program));
  });
  state_->observer = mapper->AddObserver(vtkCommand::UpdateShaderEvent, state_->feed);
}

ActorDeformation::~ActorDeformation() {
  state_->mapper->RemoveObserver(state_->observer);
  vtkShaderProperty* shaders = state_->actor->GetShaderProperty();
  shaders->ClearVertexShaderReplacement(normal_dec, true);
  shaders->ClearVertexShaderReplacement(position_impl, true);
  shaders->ClearFragmentShaderReplacement(normal_dec, true);
  shaders->ClearFragmentShaderReplacement(normal_impl, false);
}

int ActorDeformation::set(std::span<const Dent> dents) noexcept {
  state_->count = int(std::min<std::size_t>(dents.size(), std::size_t(state_->slots)));
  std::copy_n(dents.begin(), state_->count, state_->dents);
  return int(dents.size()) - state_->count;
}

}  // namespace palpate::vtk
