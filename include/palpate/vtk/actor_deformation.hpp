#pragma once
// palpate's deformation inside VTK 9 (the toolkit of 3D Slicer, iMSTK, MITK): one object installs the
// paper's vertex displacement and per-fragment normal tilt into a vtkActor's own shaders, through the
// actor's vtkShaderProperty (replacements in VTK's shader templates), and feeds the dents before each
// render of the actor. VTK's lighting, materials, colours and textures stay as they are: only the
// position and the normal VTK lights with change.
//
//     palpate::vtk::ActorDeformation dent(actor, renderer);     // once, the actor's mapper set
//     ...each frame:
//     dent.set({&world_dent, 1});                              // world coordinates of the renderer
//     window->Render();
//
// The math runs in VTK's view coordinates (vertexVC), so the actor's matrix and the mapper's vertex
// buffer shift and scale (VTK's precision trick, on by default) are already folded in; each render
// the dents are taken from world into view coordinates with the renderer's active camera. The actor's
// mapper must be a vtkOpenGLPolyDataMapper (what vtkPolyDataMapper makes on VTK's OpenGL2 backend)
// whose input has point normals (vtkPolyDataNormals makes them). The dent's units are the scene's (mm
// for palpate's haptics). Not thread-safe: set() on the thread that renders. Tested with VTK 9.1 on
// Mesa: solid colour, colours per point (scalars), a texture, a second actor left undeformed, an actor
// matrix, shifted and scaled buffers (tests/vtk/actor_deformation_test.cpp).
#include <memory>
#include <span>

#include "palpate/core/deform.hpp"

class vtkActor;
class vtkRenderer;

namespace palpate::vtk {

class ActorDeformation {
 public:
  // Installs the shader replacements and the observer that feeds them; `dent_slots` (1..max_dents)
  // dents at most per render. Throws palpate::Error when the actor has no mapper, a mapper that is not
  // a vtkOpenGLPolyDataMapper, or an input without point normals.
  ActorDeformation(vtkActor* actor, vtkRenderer* renderer, int dent_slots = 1);
  // Removes them: the actor draws as before.
  ~ActorDeformation();
  ActorDeformation(const ActorDeformation&) = delete;
  ActorDeformation& operator=(const ActorDeformation&) = delete;

  // The dents for the next render, in world coordinates. Returns how many were dropped (beyond the
  // slots). No allocation.
  int set(std::span<const Dent> dents) noexcept;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace palpate::vtk
