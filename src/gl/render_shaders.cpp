#include "render_shaders.hpp"

#include <string_view>

#include "palpate/gl/deform_glsl.hpp"

namespace palpate::gl {
namespace {

constexpr std::string_view vertex_body = R"glsl(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 3) in vec3 direction;  // where a dent moves the vertex (the normal, or the shared one)
uniform mat4 model;          // rigid: object frame to world
uniform mat3 normal_matrix;  // its rotation
uniform mat4 view_projection;
// The undeformed world position and normal: the fragment stage deforms them itself (one interpolated
// vector fewer than passing the displaced position too, which on a software rasterizer costs several
// percent of the frame).
out vec3 v_world;
out vec3 v_normal;
#ifdef PALPATE_VERTEX_COLORS
layout(location = 2) in vec3 color;
out vec3 v_color;
#endif
#ifdef PALPATE_DEFORM
// The geodesic falloff's surface sample (object frame): read only where the first dent is marked along
// the surface; else the attribute's constant value, unused.
layout(location = 4) in vec4 surface;
out vec4 v_surface;
#endif

void main() {
  vec3 world = (model * vec4(position, 1.0)).xyz;
  vec3 n = normalize(normal_matrix * normal);
  v_world = world;
  v_normal = n;
#ifdef PALPATE_VERTEX_COLORS
  v_color = color;
#endif
#ifdef PALPATE_DEFORM
  v_surface = palpate_surface_varying(world, vec4(normal_matrix * surface.xyz, surface.w));
  world = palpate_displace(world, normalize(normal_matrix * direction), v_surface);
#endif
  gl_Position = view_projection * vec4(world, 1.0);
}
)glsl";

// A directional light and a spot light (a head lamp by default), Phong: one reflected eye vector serves
// both highlights (Blinn's half vectors would cost a normalisation each), and the exponent 8 is taken by
// squaring (pow() costs two transcendentals per light on a software rasterizer).
constexpr std::string_view fragment_body = R"glsl(
in vec3 v_world;
in vec3 v_normal;
#ifdef PALPATE_DEFORM
in vec4 v_surface;
#endif
#ifdef PALPATE_VERTEX_COLORS
in vec3 v_color;
#else
uniform vec3 object_color;
#endif
uniform vec3 eye_position;
uniform vec3 light_direction;  // unit, toward the light
uniform vec3 light_color;
uniform vec3 spot_position;
uniform vec3 spot_direction;   // unit, along the beam
uniform vec2 spot_cos;         // cos of the outer and inner cone half-angles
uniform vec3 spot_color;
uniform vec3 ambient_color;
uniform float specular;
out vec4 fragment;

float highlight(float cosine) {
  float x = max(cosine, 0.0);
  x *= x; x *= x; x *= x;
  return x;
}

void main() {
  vec3 position = v_world;
#ifdef PALPATE_DEFORM
  vec3 n = v_normal;
  palpate_deform_fragment(position, n, v_surface);
#else
  vec3 n = normalize(v_normal);
#endif
#ifdef PALPATE_NORMALS
  fragment = vec4(n, 1.0);
#else
#ifdef PALPATE_VERTEX_COLORS
  vec3 albedo = v_color;
#else
  vec3 albedo = object_color;
#endif
  vec3 to_eye = normalize(eye_position - position);
  vec3 to_spot = spot_position - position;
  vec3 l = to_spot * inversesqrt(dot(to_spot, to_spot));
  float cone = smoothstep(spot_cos.x, spot_cos.y, -dot(l, spot_direction));
  vec3 diffuse = light_color * max(dot(n, light_direction), 0.0) + spot_color * (cone * max(dot(n, l), 0.0));
  vec3 mirrored_eye = reflect(-to_eye, n);
  vec3 shine = light_color * highlight(dot(mirrored_eye, light_direction)) +
               spot_color * (cone * highlight(dot(mirrored_eye, l)));
  fragment = vec4(albedo * (ambient_color + diffuse) + specular * shine, 1.0);
#endif
}
)glsl";

std::string header(ShaderVariant variant) {
  std::string text = "#version 450 core\n";
  if (variant.dent_slots > 0) text += "#define PALPATE_DEFORM\n";
  if (variant.normals) text += "#define PALPATE_NORMALS\n";
  if (variant.vertex_colors) text += "#define PALPATE_VERTEX_COLORS\n";
  if (variant.dent_slots > 0) text += deform_glsl(GlslDialect::uniform_block, variant.dent_slots);
  return text;
}

}  // namespace

std::string render_vertex_shader(ShaderVariant variant) {
  return header(variant) + std::string(vertex_body);
}

std::string render_fragment_shader(ShaderVariant variant) {
  return header(variant) + std::string(fragment_body);
}

std::string occlusion_proxy_vertex_shader() {
  return R"glsl(#version 450 core
layout(location = 0) in vec3 corner;     // world mm
layout(location = 1) in vec3 direction;  // a corner of the unit cube
uniform mat4 view_projection;
uniform float pad;  // mm
void main() { gl_Position = view_projection * vec4(corner + pad * direction, 1.0); }
)glsl";
}

std::string occlusion_proxy_fragment_shader() {
  return "#version 450 core\nvoid main() {}\n";
}

}  // namespace palpate::gl
