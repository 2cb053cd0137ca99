#pragma once
// palpate's renderer, a drop-in for an existing OpenGL 4.5 application: upload a scene once, then each
// frame draw it deformed by the latest contacts inside the caller's own context and currently bound
// framebuffer, with the caller's view and projection. Every piece of GL state it changes is saved and
// restored, so the application's rendering is unaffected (viewport and framebuffer are the caller's:
// it draws where the caller points it).
//
// Which dents deform which object: a Contact dents the object it touches (Contact::object) with that
// object's Material::sigma_mm, as in the paper; or the caller passes ObjectDents, a dent per object,
// explicitly. At most max_dents apply to one object; the rest are dropped and counted.
//
// An object whose Material::falloff is geodesic spreads its first dent along its surface: each frame the
// renderer marches over the patch that dent reaches (SurfacePatch: about 0.1 to 5 ms on one core, see
// docs/benchmarks.md) and uploads the vertices it changed; further dents on the object use the straight
// line. The march runs on a thread of the renderer's own (started on the first such draw, one for the
// renderer) while the calling thread draws what no dent reaches, and draw() waits for it before it draws
// the rest. That dent pushes every vertex against the contact triangle's normal and is widened where its
// slope would pass surface_dent_max_slope, and a wall it would drive the surface through gives way
// ahead of it (SurfacePatch::PushedDent), so that deep presses fold the surface through itself far less
// (palpate/core/deform.hpp, docs/design.md). Dent::along_surface in what the caller passes is ignored: the
// material decides.
//
// The deforming shaders are those of deform_glsl.hpp (world space in both stages), compiled for 1, 2, 4
// or 8 dents; the triangles beyond every dent's 4-sigma reach are drawn by the plain shader, which gives
// the same pixels (the plain and deforming shaders differ only by the deformation). The GL state it
// sets for itself: depth test LESS with writes, back faces culled (counter-clockwise front), no blending,
// filled polygons, every colour channel written; state changed: program, vertex array, GL_ARRAY_BUFFER,
// GL_UNIFORM_BUFFER and its binding dent_binding, those switches, the colour mask (all
// restored). With occlusion culling on, draw() must not be called inside the caller's own
// GL_ANY_SAMPLES_PASSED_CONSERVATIVE query or conditional rendering.
//
// Needs its OpenGL 4.5 context current when made (construction compiles its programs and throws
// palpate::Error with the driver's log if one fails), uploading and drawing; destroyed after that
// context has ended (glfwTerminate first), it leaves its GL objects to the context's end. Not
// thread-safe: use it on the thread of its context.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <span>

#include "palpate/core/contact.hpp"
#include "palpate/core/deform.hpp"
#include "palpate/core/scene.hpp"

namespace palpate::gl {

enum class Deformation {
  gpu,        // the paper: vertices displaced and normals perturbed in the shaders
  cpu_naive,  // the baseline the paper argues against: deform_mesh on the CPU each frame, uploaded
  none,       // the undeformed scene, same lighting
};

enum class Shading {
  lit,      // directional + spot light, per-object or per-vertex colour
  normals,  // debug: the world-space shading normal as the colour (use a float target to read it)
};

// Lights in eye space (x right, y up, the camera looking down -z), so they follow the camera.
struct Lighting {
  glm::vec3 direction{-0.6f, 0.55f, 0.55f};  // toward the directional light: upper left, so dents shade
  glm::vec3 color{0.62f, 0.6f, 0.57f};
  glm::vec3 spot_position_mm{0.0f, 80.0f, 0.0f};  // mm: a head lamp above the eye,
  glm::vec3 spot_direction{0.0f, -0.3f, -0.95f};  // along the beam: toward the middle of the view at 250 mm
  float spot_inner_deg = 10.0f;                   // full intensity inside, fading to zero at the outer angle
  float spot_outer_deg = 28.0f;
  glm::vec3 spot_color{0.4f, 0.39f, 0.36f};
  glm::vec3 ambient{0.12f, 0.12f, 0.13f};
  float specular = 0.3f;
};

struct DrawParams {
  Deformation deformation = Deformation::gpu;
  Shading shading = Shading::lit;
  // Draw the triangles that no dent reaches (all beyond 4 sigma) with the plain shader: the image is the
  // same, the dent work is paid only near the dents. Off: every triangle runs the deforming shader, as
  // in an application that uses the GLSL snippet on a whole mesh.
  bool skip_unreached = true;
  // Objects are drawn enclosing ones first (by bounding-box volume), and each later object only if an
  // occlusion query of its proxy passes the depth test: a convex polytope of about 1,400 triangles close
  // around its vertices, padded by its dents' depths so that it contains the dented object, drawn
  // without colour or depth writes. A brain inside a drawn skin costs no triangles. The image is the
  // same; off draws everything. An object whose proxy the near plane cuts is drawn unconditionally. The
  // query waits on the GPU (conditional rendering), not on the CPU.
  bool occlusion_culling = true;
  // Debug: read back each query after drawing and count the objects it hid (DrawResult::occlusion_culled).
  // Reading waits for the GPU to finish the frame, so leave it off in a real-time loop.
  bool read_occlusion_results = false;
  bool draw_probe = true;            // a sphere at each contact's HIP (the Contact overload only)
  bool draw_contact_points = false;  // a small sphere at each dent's contact point
  float probe_radius_mm = 1.5f;
  glm::vec3 probe_color{0.75f, 0.78f, 0.85f};
  glm::vec3 contact_point_color{1.0f, 0.8f, 0.1f};
  Lighting lighting;
};

// A dent for one object, given explicitly.
struct ObjectDent {
  int object = -1;  // scene object index
  Dent dent;
  // The triangle of the object's mesh the dent's centre lies on (Contact::triangle), for the geodesic
  // falloff; -1: unknown, found by a scan of the mesh (about 1 ms per 100,000 triangles).
  int triangle = -1;
};

struct DrawResult {
  int dropped_dents = 0;     // beyond max_dents for one object, or naming no uploaded object
  int deformed_objects = 0;  // objects that had at least one dent
  int occlusion_tested = 0;  // objects drawn under an occlusion query of their proxy (maybe culled)
  int occlusion_culled = 0;  // of those, the ones the query hid (counted with read_occlusion_results only)
  // Why a draw could show nothing, or not as the host meant, read from the state the host left bound:
  bool zero_viewport = false;           // the viewport has no area: nothing is drawn
  bool incomplete_framebuffer = false;  // the bound draw framebuffer is not complete: nothing is drawn
  bool no_depth_buffer =
      false;  // it has no depth buffer: drawn, but nearer surfaces do not hide farther ones
  bool drew_nothing() const noexcept { return zero_viewport || incomplete_framebuffer; }
};

class Renderer {
 public:
  // The indexed GL_UNIFORM_BUFFER binding point the renderer binds its dents to (restored after draw).
  static constexpr std::uint32_t dent_binding = 3;

  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads the scene's meshes, transforms and materials (replacing any earlier scene). Keeps a copy of
  // each mesh for the CPU-naive path, and builds the occlusion proxy of every visible object but the
  // first drawn (about 20 ms for the Table I brain). Allocates; throws palpate::Error for an invalid mesh.
  void upload(const Scene& scene);
  std::size_t object_count() const noexcept;

  // From the next draw on, object `object` is drawn with `material`'s sigma, colour and visibility;
  // nothing is uploaded again (its stiffness, damping and touchability are the haptic side's: see
  // HapticLoop::set_material). Throws palpate::Error for an index out of range or a sigma that is not
  // positive and finite.
  void set_material(std::size_t object, const Material& material);

  // Draws the uploaded scene with each in-contact Contact denting its object. Allocation: the GPU path
  // reuses its per-object scratch lists, which grow only in the first frames; the CPU-naive path makes
  // its buffers on its first frame and reuses them.
  DrawResult draw(const glm::mat4& view, const glm::mat4& projection, std::span<const Contact> contacts,
                  const DrawParams& options = {});
  // Draws the uploaded scene with the given dents.
  DrawResult draw(const glm::mat4& view, const glm::mat4& projection, std::span<const ObjectDent> dents,
                  const DrawParams& options = {});

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace palpate::gl
