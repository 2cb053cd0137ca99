#include "palpate/gl/renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>
#include <numeric>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "current_context.hpp"
#include "gl_state_guard.hpp"
#include "occlusion_proxy.hpp"
#include "palpate/core/error.hpp"
#include "palpate/core/shapes.hpp"
#include "palpate/core/surface_patch.hpp"
#include "palpate/gl/deform_glsl.hpp"
#include "palpate/gl/shader_program.hpp"
#include "render_shaders.hpp"
#include "side_thread.hpp"
#include "triangle_clusters.hpp"

namespace palpate::gl {
namespace {

constexpr std::size_t triangles_per_cluster = 64;
constexpr GLuint attribute_position = 0, attribute_normal = 1, attribute_color = 2, attribute_direction = 3;
constexpr GLuint attribute_surface = 4;
constexpr float occlusion_margin_mm = 0.5f;

// One linked program and where its uniforms are.
struct Program {
  ShaderProgram program;
  GLint model = -1, normal_matrix = -1, view_projection = -1, object_color = -1, eye_position = -1;
  GLint light_direction = -1, light_color = -1, spot_position = -1, spot_direction = -1, spot_cos = -1;
  GLint spot_color = -1, ambient_color = -1, specular = -1;

  explicit Program(ShaderVariant variant)
      : program(
            std::string("palpate renderer (") +
                (variant.dent_slots ? "deform " + std::to_string(variant.dent_slots) + " dents" : "plain") +
                (variant.normals ? ", normals" : ", lit") +
                (variant.vertex_colors ? ", vertex colours)" : ")"),
            render_vertex_shader(variant), render_fragment_shader(variant)) {
    model = program.uniform("model");
    normal_matrix = program.uniform("normal_matrix");
    view_projection = program.uniform("view_projection");
    object_color = program.uniform("object_color");
    eye_position = program.uniform("eye_position");
    light_direction = program.uniform("light_direction");
    light_color = program.uniform("light_color");
    spot_position = program.uniform("spot_position");
    spot_direction = program.uniform("spot_direction");
    spot_cos = program.uniform("spot_cos");
    spot_color = program.uniform("spot_color");
    ambient_color = program.uniform("ambient_color");
    specular = program.uniform("specular");
  }

  void set_object(const glm::mat4& transform, glm::vec3 color) const noexcept {
    const GLuint id = program.id();
    const glm::mat3 rotation(transform);
    glProgramUniformMatrix4fv(id, model, 1, GL_FALSE, glm::value_ptr(transform));
    glProgramUniformMatrix3fv(id, normal_matrix, 1, GL_FALSE, glm::value_ptr(rotation));
    glProgramUniform3fv(id, object_color, 1, glm::value_ptr(color));
  }
};

// Deforming programs come for 1, 2, 4 and 8 dent slots: a dent costs its slot in every fragment on a
// software rasterizer, so an object with one dent gets the one-slot program.
constexpr int slot_counts[] = {0, 1, 2, 4, 8};
constexpr std::size_t program_count = 4 * std::size(slot_counts);

ShaderVariant program_variant(std::size_t index) {
  return {slot_counts[index / 4], (index & 2) != 0, (index & 1) != 0};
}

std::size_t program_index(int dents, bool normals, bool vertex_colors) {
  std::size_t slots = 0;
  while (slot_counts[slots] < dents) ++slots;
  return 4 * slots + (normals ? 2u : 0u) + (vertex_colors ? 1u : 0u);
}

// Ranges of the index buffer for one glMultiDrawElements call.
struct DrawRanges {
  std::vector<GLsizei> counts;
  std::vector<const void*> offsets;

  void clear() noexcept {
    counts.clear();
    offsets.clear();
  }
  // Appends the range, merging it with the last one when they touch.
  void add(std::uint32_t first_index, std::uint32_t index_count) {
    const auto* offset =
        reinterpret_cast<const void*>(static_cast<std::uintptr_t>(first_index) * sizeof(std::uint32_t));
    if (!counts.empty() &&
        static_cast<const char*>(offsets.back()) + counts.back() * sizeof(std::uint32_t) == offset) {
      counts.back() += static_cast<GLsizei>(index_count);
      return;
    }
    counts.push_back(static_cast<GLsizei>(index_count));
    offsets.push_back(offset);
  }
  void draw() const noexcept {
    if (!counts.empty()) {
      glMultiDrawElements(GL_TRIANGLES, counts.data(), GL_UNSIGNED_INT, offsets.data(),
                          static_cast<GLsizei>(counts.size()));
    }
  }
};

// A mesh in GPU buffers: interleaved position + normal, optional colours, indices.
struct GpuMesh {
  GLuint vertex_array = 0, vertex_buffer = 0, color_buffer = 0, direction_buffer = 0, index_buffer = 0;
  GLsizei index_count = 0;

  explicit GpuMesh(const Mesh& mesh) {
    std::vector<glm::vec3> interleaved(2 * mesh.positions_mm.size());
    for (std::size_t i = 0; i < mesh.positions_mm.size(); ++i) {
      interleaved[2 * i] = mesh.positions_mm[i];
      interleaved[2 * i + 1] = mesh.normals[i];
    }
    glCreateVertexArrays(1, &vertex_array);
    glCreateBuffers(1, &vertex_buffer);
    glNamedBufferStorage(vertex_buffer, static_cast<GLsizeiptr>(interleaved.size() * sizeof(glm::vec3)),
                         interleaved.data(), 0);
    glVertexArrayVertexBuffer(vertex_array, 0, vertex_buffer, 0, 2 * sizeof(glm::vec3));
    glEnableVertexArrayAttrib(vertex_array, attribute_position);
    glVertexArrayAttribFormat(vertex_array, attribute_position, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vertex_array, attribute_position, 0);
    glEnableVertexArrayAttrib(vertex_array, attribute_normal);
    glVertexArrayAttribFormat(vertex_array, attribute_normal, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3));
    glVertexArrayAttribBinding(vertex_array, attribute_normal, 0);
    // The displacement direction: the mesh's shared one where its vertices are split, else the normal.
    glEnableVertexArrayAttrib(vertex_array, attribute_direction);
    if (mesh.directions.empty()) {
      glVertexArrayAttribFormat(vertex_array, attribute_direction, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3));
      glVertexArrayAttribBinding(vertex_array, attribute_direction, 0);
    } else {
      glCreateBuffers(1, &direction_buffer);
      glNamedBufferStorage(direction_buffer,
                           static_cast<GLsizeiptr>(mesh.directions.size() * sizeof(glm::vec3)),
                           mesh.directions.data(), 0);
      glVertexArrayVertexBuffer(vertex_array, 2, direction_buffer, 0, sizeof(glm::vec3));
      glVertexArrayAttribFormat(vertex_array, attribute_direction, 3, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(vertex_array, attribute_direction, 2);
    }
    if (!mesh.colors.empty()) {
      glCreateBuffers(1, &color_buffer);
      glNamedBufferStorage(color_buffer, static_cast<GLsizeiptr>(mesh.colors.size() * sizeof(glm::vec3)),
                           mesh.colors.data(), 0);
      glVertexArrayVertexBuffer(vertex_array, 1, color_buffer, 0, sizeof(glm::vec3));
      glEnableVertexArrayAttrib(vertex_array, attribute_color);
      glVertexArrayAttribFormat(vertex_array, attribute_color, 3, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(vertex_array, attribute_color, 1);
    }
    glCreateBuffers(1, &index_buffer);
    glNamedBufferStorage(index_buffer, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                         mesh.indices.data(), 0);
    glVertexArrayElementBuffer(vertex_array, index_buffer);
    index_count = static_cast<GLsizei>(mesh.indices.size());
  }
  ~GpuMesh() {
    if (!a_context_is_current()) return;
    const GLuint buffers[] = {vertex_buffer, color_buffer, direction_buffer, index_buffer};
    glDeleteBuffers(4, buffers);
    glDeleteVertexArrays(1, &vertex_array);
  }
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
};

// The CPU-naive path's buffers: world positions and normals rewritten every frame, the object's indices.
struct NaiveBuffers {
  GLuint vertex_array = 0, position_buffer = 0, normal_buffer = 0;

  NaiveBuffers(std::size_t vertices, GLuint index_buffer, GLuint color_buffer) {
    const auto bytes = static_cast<GLsizeiptr>(vertices * sizeof(glm::vec3));
    glCreateVertexArrays(1, &vertex_array);
    glCreateBuffers(1, &position_buffer);
    glCreateBuffers(1, &normal_buffer);
    glNamedBufferData(position_buffer, bytes, nullptr, GL_STREAM_DRAW);
    glNamedBufferData(normal_buffer, bytes, nullptr, GL_STREAM_DRAW);
    const GLuint buffers[] = {position_buffer, normal_buffer, color_buffer};
    const GLuint attributes[] = {attribute_position, attribute_normal, attribute_color};
    for (GLuint i = 0; i < (color_buffer ? 3u : 2u); ++i) {
      glVertexArrayVertexBuffer(vertex_array, i, buffers[i], 0, sizeof(glm::vec3));
      glEnableVertexArrayAttrib(vertex_array, attributes[i]);
      glVertexArrayAttribFormat(vertex_array, attributes[i], 3, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(vertex_array, attributes[i], i);
    }
    glVertexArrayElementBuffer(vertex_array, index_buffer);
  }
  ~NaiveBuffers() {
    if (!a_context_is_current()) return;
    const GLuint buffers[] = {position_buffer, normal_buffer};
    glDeleteBuffers(2, buffers);
    glDeleteVertexArrays(1, &vertex_array);
  }
  NaiveBuffers(const NaiveBuffers&) = delete;
  NaiveBuffers& operator=(const NaiveBuffers&) = delete;
};

// The dents of one object in a uniform buffer, laid out as deform_glsl's PalpateDeform block.
struct DentBuffer {
  GLuint id = 0;
  DentBuffer() {
    const DeformBlockData empty{};
    glCreateBuffers(1, &id);
    glNamedBufferData(id, sizeof(DeformBlockData), &empty, GL_DYNAMIC_DRAW);
  }
  ~DentBuffer() {
    if (a_context_is_current()) glDeleteBuffers(1, &id);
  }
  DentBuffer(const DentBuffer&) = delete;
  DentBuffer& operator=(const DentBuffer&) = delete;

  void update(std::span<const Dent> dents) const noexcept {
    const DeformBlockData data = make_deform_block_data(dents);
    glNamedBufferSubData(id, 0, sizeof(DeformBlockData), &data);
    glBindBufferBase(GL_UNIFORM_BUFFER, Renderer::dent_binding, id);
  }
};

// The geodesic falloff of one object: its patch, marched on the CPU each frame, and the per-vertex
// surface samples in a vertex buffer (attribute_surface of the object's vertex array), of which each frame
// uploads the vertices the patch changed.
struct SurfaceFalloff {
  SurfacePatch patch;
  GLuint buffer = 0;
  // Per cluster of the mesh's triangles: how much further than the dent's 4 sigma it may move a corner there.
  std::vector<float> cluster_wall_reach_mm;

  SurfaceFalloff(const Mesh& mesh, GLuint vertex_array, std::span<const TriangleCluster> clusters)
      : patch(mesh) {
    for (const TriangleCluster& cluster : clusters) {
      float reach = 0.0f;
      for (std::uint32_t i = cluster.first_index; i < cluster.first_index + cluster.index_count; i += 3)
        reach = std::max(reach, patch.wall_reach_mm(i / 3));
      cluster_wall_reach_mm.push_back(reach);
    }
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, static_cast<GLsizeiptr>(patch.samples().size_bytes()),
                         patch.samples().data(), GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(vertex_array, 3, buffer, 0, sizeof(glm::vec4));
    glEnableVertexArrayAttrib(vertex_array, attribute_surface);
    glVertexArrayAttribFormat(vertex_array, attribute_surface, 4, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vertex_array, attribute_surface, 3);
  }
  ~SurfaceFalloff() {
    if (a_context_is_current()) glDeleteBuffers(1, &buffer);
  }
  SurfaceFalloff(const SurfaceFalloff&) = delete;
  SurfaceFalloff& operator=(const SurfaceFalloff&) = delete;

  // Marches from `dent` (world, widened by dent_with_slope_limit) on `triangle` (the object's, in the
  // renderer's order; -1: unknown): the dent falls off along the surface, pushing every vertex against the
  // contact triangle's normal, and walls it would pass through give way. The transform is rigid: depth and
  // sigma are the same in the object frame. No GL: it may run on another thread.
  void compute(const Dent& dent, const glm::mat4& transform, std::int64_t triangle) noexcept {
    const glm::vec3 point = glm::vec3(glm::inverse(transform) * glm::vec4(dent.center_mm, 1.0f));
    patch.compute(triangle, point, SurfacePatch::PushedDent{dent.depth_mm, dent.sigma_mm});
  }
  // Uploads what compute() changed, and makes the dent one along the surface.
  void upload(Dent& dent, const glm::mat4& transform) {
    const SurfacePatch::Range changed = patch.changed();
    if (changed.count > 0) {
      glNamedBufferSubData(buffer, static_cast<GLintptr>(changed.first * sizeof(glm::vec4)),
                           static_cast<GLsizeiptr>(changed.count * sizeof(glm::vec4)),
                           patch.samples().data() + changed.first);
    }
    dent.along_surface = true;
    dent.normal = glm::mat3(transform) * patch.contact_normal();
  }
};

// An occlusion query object.
struct Query {
  GLuint id = 0;
  Query() { glCreateQueries(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, 1, &id); }
  ~Query() {
    if (a_context_is_current()) glDeleteQueries(1, &id);
  }
  Query(const Query&) = delete;
  Query& operator=(const Query&) = delete;
};

// An occlusion proxy in GPU buffers: corners as positions, pad directions as normals.
struct GpuProxy {
  OcclusionProxy shape;
  GpuMesh mesh;

  explicit GpuProxy(OcclusionProxy proxy) : shape(std::move(proxy)), mesh(as_mesh(shape)) {}

  static Mesh as_mesh(const OcclusionProxy& proxy) {
    Mesh mesh;
    mesh.positions_mm = proxy.corners;
    mesh.normals = proxy.directions;
    mesh.indices = proxy.indices;
    return mesh;
  }
};

// The occlusion queries' program.
struct ProxyProgram {
  ShaderProgram program{"palpate renderer (occlusion proxy)", occlusion_proxy_vertex_shader(),
                        occlusion_proxy_fragment_shader()};
  GLint view_projection = program.uniform("view_projection");
  GLint pad = program.uniform("pad");
};

struct RenderObject {
  Mesh mesh;  // object frame, triangles in cluster order (the CPU-naive path deforms it)
  glm::mat4 transform{1.0f};
  Bounds world_bounds;              // undeformed
  std::unique_ptr<GpuProxy> proxy;  // none: never culled
  Query occlusion;
  bool queried = false;  // in the last draw
  Material material;
  std::vector<TriangleCluster> clusters;
  std::vector<glm::vec3> cluster_centers;  // world
  std::unique_ptr<GpuMesh> gpu;
  std::unique_ptr<NaiveBuffers> naive;  // made on first CPU-naive draw
  Mesh deformed;                        // the CPU-naive path's scratch
  DentBuffer dent_buffer;
  std::array<Dent, max_dents> dents{};
  int dent_count = 0;
  std::int64_t first_dent_triangle = -1;         // the first dent's triangle (renderer's order), -1: unknown
  std::vector<std::uint32_t> triangle_moved_to;  // the scene mesh's triangle t is triangle_moved_to[t] here
  std::unique_ptr<SurfaceFalloff> surface;       // made when the material first asks for the geodesic falloff
  DrawRanges reached, unreached;                 // per-frame scratch
  std::vector<std::uint32_t> undecided;          // per-frame scratch: clusters only a wall may reach
};

}  // namespace

struct Renderer::State {
  std::vector<Program> programs;   // indexed by program_index
  std::unique_ptr<GpuMesh> probe;  // unit sphere for the probe and contact-point markers
  std::unique_ptr<ProxyProgram> proxy_program;
  std::vector<std::unique_ptr<RenderObject>> objects;
  std::vector<std::size_t> draw_order;  // enclosing objects first
  // Made on the first geodesic draw; the last member, so that it stops before what its task reads goes.
  std::unique_ptr<SideThread> side_thread;

  // The program for `dents` dents (0: the plain program).
  const Program& program(int dents, Shading shading, bool vertex_colors) const {
    return programs[program_index(dents, shading == Shading::normals, vertex_colors)];
  }
  // The uploaded object of that index, or null.
  RenderObject* object_at(int index) const noexcept {
    return index >= 0 && static_cast<std::size_t>(index) < objects.size()
               ? objects[static_cast<std::size_t>(index)].get()
               : nullptr;
  }
  // Adds a dent to the object's list, with the triangle it lies on (the scene mesh's, -1: unknown);
  // returns 1 when the dent is dropped (no such object, or its list is full).
  int add_dent(int object_index, const Dent& dent, int triangle) noexcept;
  void render(const glm::mat4& view, const glm::mat4& projection, const DrawParams& options,
              std::span<const Contact> probes, DrawResult& result);
  // Draws the object's proxy, padded by its dents, into its occlusion query (front faces, no colour, no
  // depth written) and starts conditional rendering on it. False, and nothing started, where the near
  // plane cuts the proxy: its front faces there are clipped away and could no longer vouch for the object.
  bool begin_occlusion_test(RenderObject& object, const glm::mat4& view_projection) const;
};

Renderer::Renderer() : state_(std::make_unique<State>()) {
  state_->programs.reserve(program_count);
  for (std::size_t i = 0; i < program_count; ++i) state_->programs.emplace_back(program_variant(i));
  for (std::size_t i = 4; i < program_count; ++i) {
    const GLuint id = state_->programs[i].program.id();
    glUniformBlockBinding(id, glGetUniformBlockIndex(id, deform_block_name), Renderer::dent_binding);
  }
  state_->probe = std::make_unique<GpuMesh>(make_sphere(1.0f, 642));
  state_->proxy_program = std::make_unique<ProxyProgram>();
}

Renderer::~Renderer() = default;

void Renderer::upload(const Scene& scene) {
  std::vector<std::unique_ptr<RenderObject>> objects;
  objects.reserve(scene.objects.size());
  for (const SceneObject& source : scene.objects) {
    const std::string what = "scene object '" + source.name + "'";
    validate_mesh(source.mesh, what);
    if (!(source.material.sigma_mm > 0.0f) || !std::isfinite(source.material.sigma_mm)) {
      throw Error(what + ": sigma must be positive and finite, got " +
                  std::to_string(source.material.sigma_mm));
    }
    auto object = std::make_unique<RenderObject>();
    object->mesh = source.mesh;
    object->transform = source.transform;
    object->material = source.material;
    object->clusters = cluster_triangles(object->mesh.indices, object->mesh.positions_mm,
                                         triangles_per_cluster, &object->triangle_moved_to);
    order_vertices_by_first_use(object->mesh);
    for (const TriangleCluster& cluster : object->clusters) {
      object->cluster_centers.push_back(glm::vec3(object->transform * glm::vec4(cluster.center, 1.0f)));
    }
    object->gpu = std::make_unique<GpuMesh>(object->mesh);
    if (source.material.falloff == Falloff::geodesic) {
      object->surface =
          std::make_unique<SurfaceFalloff>(object->mesh, object->gpu->vertex_array, object->clusters);
    }
    object->world_bounds = world_bounds(source);
    objects.push_back(std::move(object));
  }
  // Enclosing objects first, so that what they hide can be culled.
  std::vector<std::size_t> order(objects.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto volume = [&](std::size_t i) {
    const glm::vec3 size = objects[i]->world_bounds.size_mm();
    return size.x * size.y * size.z;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return volume(a) > volume(b); });
  // Every object but the first in drawing order may be culled (behind it, or behind another when it is
  // hidden: visibility changes without an upload): those get a proxy.
  for (const std::size_t index : order) {
    RenderObject& object = *objects[index];
    if (index != order.front()) {
      const SceneObject& source = scene.objects[index];
      std::vector<glm::vec3> world(source.mesh.positions_mm.size());
      std::transform(source.mesh.positions_mm.begin(), source.mesh.positions_mm.end(), world.begin(),
                     [&](glm::vec3 p) { return glm::vec3(source.transform * glm::vec4(p, 1.0f)); });
      if (auto proxy = make_occlusion_proxy(world, occlusion_margin_mm)) {
        object.proxy = std::make_unique<GpuProxy>(std::move(*proxy));
      }
    }
  }
  state_->objects = std::move(objects);
  state_->draw_order = std::move(order);
}

std::size_t Renderer::object_count() const noexcept {
  return state_->objects.size();
}

void Renderer::set_material(std::size_t object, const Material& material) {
  if (object >= state_->objects.size()) {
    throw Error("renderer: set_material: object " + std::to_string(object) + " out of range (" +
                std::to_string(state_->objects.size()) + " uploaded)");
  }
  if (!(material.sigma_mm > 0.0f) || !std::isfinite(material.sigma_mm)) {
    throw Error("renderer: set_material: sigma must be positive and finite, got " +
                std::to_string(material.sigma_mm));
  }
  RenderObject& target = *state_->objects[object];
  if (material.falloff == Falloff::geodesic && !target.surface) {
    target.surface = std::make_unique<SurfaceFalloff>(target.mesh, target.gpu->vertex_array, target.clusters);
  }
  target.material = material;
}

namespace {

// Per-frame uniforms shared by every program: camera and lights, in world space.
struct FrameUniforms {
  glm::mat4 view_projection;
  glm::vec3 eye, light_direction, spot_position, spot_direction;
  glm::vec2 spot_cos;

  FrameUniforms(const glm::mat4& view, const glm::mat4& projection, const Lighting& lighting) {
    const glm::mat4 eye_to_world = glm::inverse(view);
    const glm::mat3 eye_to_world_rotation(eye_to_world);
    view_projection = projection * view;
    eye = glm::vec3(eye_to_world[3]);
    light_direction = glm::normalize(eye_to_world_rotation * lighting.direction);
    spot_position = glm::vec3(eye_to_world * glm::vec4(lighting.spot_position_mm, 1.0f));
    spot_direction = glm::normalize(eye_to_world_rotation * lighting.spot_direction);
    spot_cos = {std::cos(glm::radians(lighting.spot_outer_deg)),
                std::cos(glm::radians(lighting.spot_inner_deg))};
  }

  void set(const Program& p, const Lighting& lighting) const noexcept {
    const GLuint id = p.program.id();
    glProgramUniformMatrix4fv(id, p.view_projection, 1, GL_FALSE, glm::value_ptr(view_projection));
    glProgramUniform3fv(id, p.eye_position, 1, glm::value_ptr(eye));
    glProgramUniform3fv(id, p.light_direction, 1, glm::value_ptr(light_direction));
    glProgramUniform3fv(id, p.light_color, 1, glm::value_ptr(lighting.color));
    glProgramUniform3fv(id, p.spot_position, 1, glm::value_ptr(spot_position));
    glProgramUniform3fv(id, p.spot_direction, 1, glm::value_ptr(spot_direction));
    glProgramUniform2fv(id, p.spot_cos, 1, glm::value_ptr(spot_cos));
    glProgramUniform3fv(id, p.spot_color, 1, glm::value_ptr(lighting.spot_color));
    glProgramUniform3fv(id, p.ambient_color, 1, glm::value_ptr(lighting.ambient));
    glProgramUniform1f(id, p.specular, lighting.specular);
  }
};

// What a cluster's centre adds to a reach: its radius, and a little slack so that rounding can only ever
// send a cluster to the deforming side.
float cluster_slack(const TriangleCluster& cluster) noexcept {
  return cluster.radius * 1.001f + 1e-3f;
}

// Splits the object's clusters into those some dent reaches and those none does. A first dent along the
// surface may also move a wall's corner beyond its 4 sigma (SurfacePatch::wall_reach_mm): the clusters
// only that could reach are left undecided until the patch is known (settle_clusters).
void classify_clusters(RenderObject& object, bool along_surface) {
  object.reached.clear();
  object.unreached.clear();
  object.undecided.clear();
  for (std::size_t c = 0; c < object.clusters.size(); ++c) {
    const TriangleCluster& cluster = object.clusters[c];
    bool reached = false, maybe = false;
    for (int i = 0; i < object.dent_count && !reached; ++i) {
      const Dent& dent = object.dents[static_cast<std::size_t>(i)];
      const float reach = dent_cutoff_sigmas * dent.sigma_mm + cluster_slack(cluster);
      const float distance = glm::distance(object.cluster_centers[c], dent.center_mm);
      reached = distance < reach;
      if (along_surface && i == 0) maybe = distance < reach + object.surface->cluster_wall_reach_mm[c];
    }
    if (!reached && maybe) {
      object.undecided.push_back(static_cast<std::uint32_t>(c));
    } else {
      (reached ? object.reached : object.unreached).add(cluster.first_index, cluster.index_count);
    }
  }
}

// Sends the undecided clusters to the deforming side where the patch moved a vertex that far from the first
// dent's contact, else to the plain side (emptied first: what it held is drawn).
void settle_clusters(RenderObject& object) {
  object.unreached.clear();
  const float moved = object.surface->patch.moved_reach_mm();
  for (const std::uint32_t c : object.undecided) {
    const TriangleCluster& cluster = object.clusters[c];
    const float reach = moved + cluster_slack(cluster);
    const bool reached = glm::distance(object.cluster_centers[c], object.dents[0].center_mm) < reach;
    (reached ? object.reached : object.unreached).add(cluster.first_index, cluster.index_count);
  }
}

void draw_all(const GpuMesh& mesh) noexcept {
  glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
}

void set_draw_state() noexcept {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glDisable(GL_BLEND);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

// A sphere of `radius` at `center`, for the probe and the contact points.
void draw_marker(const Program& program, const GpuMesh& sphere, glm::vec3 center, float radius,
                 glm::vec3 color) {
  program.set_object(glm::scale(glm::translate(glm::mat4(1.0f), center), glm::vec3(radius)), color);
  draw_all(sphere);
}

}  // namespace

bool Renderer::State::begin_occlusion_test(RenderObject& object, const glm::mat4& view_projection) const {
  if (!object.proxy) return false;
  // A vertex moves by at most the sum of its dents' depths (along its normal, G <= p each). The proxy
  // holds the margin besides, for rounding here and in the rasterizer.
  float pad = 0.0f;
  for (int i = 0; i < object.dent_count; ++i)
    pad += std::abs(object.dents[static_cast<std::size_t>(i)].depth_mm);
  // The near plane, clip z + w >= 0, scaled to world millimetres. A convex proxy with every vertex at
  // least the margin beyond it is not clipped there (NaN fails the test too: drawn unconditionally).
  const glm::vec4 near_plane = glm::row(view_projection, 2) + glm::row(view_projection, 3);
  const glm::vec4 near_mm = near_plane / glm::length(glm::vec3(near_plane));
  const OcclusionProxy& shape = object.proxy->shape;
  for (std::size_t i = 0; i < shape.corners.size(); ++i) {
    if (!(glm::dot(near_mm, glm::vec4(shape.vertex(i, pad), 1.0f)) >= occlusion_margin_mm)) return false;
  }

  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glUseProgram(proxy_program->program.id());
  glProgramUniform1f(proxy_program->program.id(), proxy_program->pad, pad);
  glBindVertexArray(object.proxy->mesh.vertex_array);
  glBeginQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, object.occlusion.id);
  draw_all(object.proxy->mesh);
  glEndQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  // Waits for the query on the GPU: on llvmpipe the result is not there yet without waiting.
  glBeginConditionalRender(object.occlusion.id, GL_QUERY_WAIT);
  return true;
}

DrawResult Renderer::draw(const glm::mat4& view, const glm::mat4& projection,
                          std::span<const Contact> contacts, const DrawParams& options) {
  DrawResult result;
  for (auto& object : state_->objects) object->dent_count = 0;
  for (const Contact& contact : contacts) {
    if (!contact.in_contact()) continue;
    const RenderObject* object = state_->object_at(contact.object);
    result.dropped_dents +=
        object ? state_->add_dent(contact.object, dent_from_contact(contact, object->material.sigma_mm),
                                  contact.triangle)
               : 1;
  }
  state_->render(view, projection, options, options.draw_probe ? contacts : std::span<const Contact>(),
                 result);
  return result;
}

DrawResult Renderer::draw(const glm::mat4& view, const glm::mat4& projection,
                          std::span<const ObjectDent> dents, const DrawParams& options) {
  DrawResult result;
  for (auto& object : state_->objects) object->dent_count = 0;
  for (const ObjectDent& entry : dents) {
    result.dropped_dents += state_->add_dent(entry.object, entry.dent, entry.triangle);
  }
  state_->render(view, projection, options, {}, result);
  return result;
}

int Renderer::State::add_dent(int object_index, const Dent& dent, int triangle) noexcept {
  RenderObject* object = object_at(object_index);
  if (!object || object->dent_count == max_dents) return 1;
  if (object->dent_count == 0) {
    object->first_dent_triangle = triangle >= 0 && std::size_t(triangle) < object->triangle_moved_to.size()
                                      ? object->triangle_moved_to[std::size_t(triangle)]
                                      : -1;
  }
  Dent& added = object->dents[static_cast<std::size_t>(object->dent_count++)];
  added = dent;
  added.along_surface = false;  // the geodesic falloff is the object's material's to choose (and its normal)
  return 0;
}

namespace {

// What the host left bound that would keep a draw from showing (DrawResult's flags).
void check_target(DrawResult& result) noexcept {
  GLint viewport[4] = {};
  glGetIntegerv(GL_VIEWPORT, viewport);
  result.zero_viewport = viewport[2] <= 0 || viewport[3] <= 0;
  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  result.incomplete_framebuffer =
      glCheckNamedFramebufferStatus(GLuint(framebuffer), GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE;
  GLint depth_bits = 0;
  if (framebuffer == 0) {
    glGetNamedFramebufferAttachmentParameteriv(0, GL_DEPTH, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE,
                                               &depth_bits);
  } else {
    GLint type = GL_NONE;
    glGetNamedFramebufferAttachmentParameteriv(GLuint(framebuffer), GL_DEPTH_ATTACHMENT,
                                               GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    if (type != GL_NONE) {
      glGetNamedFramebufferAttachmentParameteriv(GLuint(framebuffer), GL_DEPTH_ATTACHMENT,
                                                 GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &depth_bits);
    }
  }
  result.no_depth_buffer = depth_bits == 0;
}

}  // namespace

void Renderer::State::render(const glm::mat4& view, const glm::mat4& projection, const DrawParams& options,
                             std::span<const Contact> probes, DrawResult& result) {
  check_target(result);
  if (result.drew_nothing()) return;
  const GlStateGuard guard(Renderer::dent_binding);
  set_draw_state();
  const FrameUniforms frame(view, projection, options.lighting);
  for (const Program& p : programs) frame.set(p, options.lighting);
  glProgramUniformMatrix4fv(proxy_program->program.id(), proxy_program->view_projection, 1, GL_FALSE,
                            glm::value_ptr(frame.view_projection));

  bool drawn_before = false;
  for (const std::size_t index : draw_order) {
    RenderObject& object = *objects[index];
    object.queried = false;
    if (!object.material.visible) continue;
    const bool query =
        options.occlusion_culling && drawn_before && begin_occlusion_test(object, frame.view_projection);
    drawn_before = true;
    object.queried = query;
    if (query) ++result.occlusion_tested;
    const bool colors = object.gpu->color_buffer != 0;
    const Program& plain = program(0, options.shading, colors);
    const std::span<const Dent> object_dents(object.dents.data(),
                                             static_cast<std::size_t>(object.dent_count));
    if (object.dent_count > 0) ++result.deformed_objects;
    const bool along_surface = object.material.falloff == Falloff::geodesic && object.surface &&
                               object.dent_count > 0 && options.deformation != Deformation::none;
    // Widened before anything reads how far it reaches.
    if (along_surface) object.dents[0] = dent_with_slope_limit(object.dents[0], surface_dent_max_slope);
    const auto march = [&object]() noexcept {
      object.surface->compute(object.dents[0], object.transform, object.first_dent_triangle);
    };

    if (object.dent_count == 0 || options.deformation == Deformation::none) {
      plain.set_object(object.transform, object.material.color);
      glUseProgram(plain.program.id());
      glBindVertexArray(object.gpu->vertex_array);
      draw_all(*object.gpu);
    } else if (options.deformation == Deformation::cpu_naive) {
      if (along_surface) {
        march();
        object.surface->upload(object.dents[0], object.transform);
      }
      deform_mesh(object.mesh, object.transform, object_dents, object.deformed,
                  along_surface ? object.surface->patch.samples() : std::span<const glm::vec4>());
      if (!object.naive) {
        object.naive = std::make_unique<NaiveBuffers>(object.mesh.vertex_count(), object.gpu->index_buffer,
                                                      object.gpu->color_buffer);
      }
      const auto bytes = static_cast<GLsizeiptr>(object.deformed.positions_mm.size() * sizeof(glm::vec3));
      glNamedBufferSubData(object.naive->position_buffer, 0, bytes, object.deformed.positions_mm.data());
      glNamedBufferSubData(object.naive->normal_buffer, 0, bytes, object.deformed.normals.data());
      plain.set_object(glm::mat4(1.0f), object.material.color);  // deform_mesh gives world coordinates
      glUseProgram(plain.program.id());
      glBindVertexArray(object.naive->vertex_array);
      draw_all(*object.gpu);
    } else {
      const Program& deform = program(object.dent_count, options.shading, colors);
      deform.set_object(object.transform, object.material.color);
      glBindVertexArray(object.gpu->vertex_array);
      // The side thread marches the patch while this one draws what no dent reaches (on llvmpipe this
      // thread runs that draw's vertex stage), and the GPU goes on with it while this one waits.
      const bool beside = along_surface && options.skip_unreached;
      if (beside) {
        if (!side_thread) side_thread = std::make_unique<SideThread>();
        side_thread->start(march);
      } else if (along_surface) {
        march();
      }
      if (options.skip_unreached) {
        classify_clusters(object, along_surface);
        plain.set_object(object.transform, object.material.color);
        glUseProgram(plain.program.id());
        object.unreached.draw();
      }
      if (beside) {
        glFlush();
        side_thread->wait();
        settle_clusters(object);
        object.unreached.draw();  // with the plain program still
      }
      if (along_surface) object.surface->upload(object.dents[0], object.transform);
      object.dent_buffer.update(object_dents);
      glUseProgram(deform.program.id());
      if (options.skip_unreached) {
        object.reached.draw();
      } else {
        draw_all(*object.gpu);
      }
    }
    if (query) glEndConditionalRender();
  }

  if (options.read_occlusion_results) {
    for (const auto& object : objects) {
      if (!object->queried) continue;
      GLuint any_sample_passed = GL_TRUE;
      glGetQueryObjectuiv(object->occlusion.id, GL_QUERY_RESULT, &any_sample_passed);
      if (!any_sample_passed) ++result.occlusion_culled;
    }
  }

  const Program& marker = program(0, options.shading, false);
  glUseProgram(marker.program.id());
  glBindVertexArray(probe->vertex_array);
  for (const Contact& contact : probes) {
    draw_marker(marker, *probe, contact.hip_mm, options.probe_radius_mm, options.probe_color);
  }
  if (options.draw_contact_points) {
    for (const auto& object : objects) {
      for (int i = 0; i < object->dent_count; ++i) {
        draw_marker(marker, *probe, object->dents[static_cast<std::size_t>(i)].center_mm,
                    0.5f * options.probe_radius_mm, options.contact_point_color);
      }
    }
  }
}

}  // namespace palpate::gl
