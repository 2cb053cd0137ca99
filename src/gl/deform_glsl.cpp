#include "palpate/gl/deform_glsl.hpp"

#include <algorithm>
#include <string>

#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

// The formulas of palpate/core/deform.cpp, written for SIMD shader cores: squared distances are
// compared before anything is computed, and the normal is tilted without trigonometry (see below).
// The dent data, one declaration per dialect; the functions read it by the same names in both.
constexpr std::string_view uniform_block = R"glsl(layout(std140) uniform PalpateDeform {
  vec4 palpate_dent_center_depth[PALPATE_MAX_DENTS];  // xyz contact point c, w penetration p
  vec4 palpate_dent_shape[PALPATE_MAX_DENTS];         // x (4 sigma)^2, y 1/(2 sigma^2), z p/sigma^2, w sigma
  int palpate_dent_count;
  int palpate_surface_dent;     // 1: the first dent falls off along the surface (the vertex's surface sample)
  vec4 palpate_surface_normal;  // xyz: the direction it pushes every vertex against (zero: their own)
};
)glsl";
constexpr std::string_view uniform_arrays =
    R"glsl(uniform vec4 palpate_dent_center_depth[PALPATE_MAX_DENTS];  // xyz c, w p
uniform vec4 palpate_dent_shape[PALPATE_MAX_DENTS];  // x (4 sigma)^2, y 1/(2 sigma^2), z p/sigma^2, w sigma
uniform int palpate_dent_count;
uniform int palpate_surface_dent;    // 1: the first dent falls off along the surface (the surface sample)
uniform vec4 palpate_surface_normal;  // xyz: the direction it pushes every vertex against (zero: their own)
)glsl";

// The functions, in the GLSL common to 1.10 and later (and ES 3.00). Their loops run over
// PALPATE_DENT_SLOTS slots so that the data is read at constant offsets (a software rasterizer gathers
// lane by lane from a dynamic index); dents past the slots are ignored.
constexpr std::string_view functions =
    R"glsl(// The vertex stage's first step for a dent along the surface: from the vertex's surface sample (xyz the
// unit direction toward the contact along the surface, w the distance along it; the space's units),
// what the surface adds to the straight line from the vertex to the first dent's contact
// (palpate/core/deform.hpp). Hand it to palpate_displace and, interpolated, to the fragment stage's
// functions: unlike the distance itself, it interpolates well up to the contact.
vec4 palpate_surface_varying(vec3 position, vec4 surface) {
  vec3 to_contact = palpate_dent_center_depth[0].xyz - position;
  float e = length(to_contact);
  float along = surface.w;
  return vec4(surface.xyz * along - to_contact, along - e);
}

// The distance d of the first dent along the surface, from the straight line e and the varying above;
// `toward` (VC) becomes the vector whose tangential part points the way to the contact.
float palpate_surface_distance(float e, vec4 surface, inout vec3 toward) {
  toward += surface.xyz;
  return e + surface.w;
}

// V' = V - D * sum G(d), G(d) = p exp(-d^2 / 2 sigma^2), d = |V - c| (or along the surface for the first
// dent, with `use_surface`); a dent is skipped beyond 4 sigma. direction must be of unit length: at
// d = 0 the surface moves by exactly p, to the tool tip.
// The first dent along the surface pushes every vertex against palpate_surface_normal when it is set.
vec3 palpate_displace_any(vec3 position, vec3 direction, vec4 surface, bool use_surface) {
  vec3 moved = position;
  for (int i = 0; i < PALPATE_DENT_SLOTS; ++i) {
    if (i >= palpate_dent_count) break;
    vec4 center_depth = palpate_dent_center_depth[i];
    vec3 offset = center_depth.xyz - position;
    float d2 = dot(offset, offset);
    vec3 push = direction;
    if (use_surface && i == 0 && palpate_surface_dent != 0) {
      float d = palpate_surface_distance(sqrt(d2), surface, offset);
      d2 = d * d;
      push = dot(palpate_surface_normal.xyz, palpate_surface_normal.xyz) > 0.0 ? palpate_surface_normal.xyz : direction;
    }
    moved -= push * (d2 < palpate_dent_shape[i].x ? center_depth.w * exp(-d2 * palpate_dent_shape[i].y) : 0.0);
  }
  return moved;
}
vec3 palpate_displace(vec3 position, vec3 direction) {
  return palpate_displace_any(position, direction, vec4(0.0), false);
}
vec3 palpate_displace(vec3 position, vec3 direction, vec4 surface) {
  return palpate_displace_any(position, direction, surface, true);
}

// The fragment stage: from the undeformed world position and normal interpolated to this fragment,
// the displaced position V - N sum G(d), evaluated here (N as interpolated: of about unit length), and
// the paper's per-fragment normal: N rotated by theta = atan(-G'(d)) toward the contact point (about
// W = N x VC; along the surface, about N x the surface sample's direction), G'(d) = -p d / sigma^2
// exp(-d^2 / 2 sigma^2), one dent after the other.
// Without trigonometry: with T = (W x N) / |W x N|, the unit tangent toward c, the rotated normal is
// cos(theta) (N + tan(theta) T); its direction is that of N + tan(theta) |N| T for any length of N, so
// the scale is dropped and the result normalised once. With K the vector toward c (VC), W x N = K |N|^2 -
// N (N.K) has the length |N| |N x K|, so the step along it is tan(theta) / |N x K| = (p / sigma^2)
// exp(-d^2 / 2 sigma^2) sqrt(d^2 / |N x K|^2), with |N x K|^2 = |N|^2 |K|^2 - (N.K)^2.
// d is measured from the undeformed position, as in palpate_displace. No tilt beyond 4 sigma, nor where
// d = 0 or N is parallel to K (|N x K|^2 <= 1e-12 |K|^2 |N|^2, as the CPU twin). The normal comes out
// of unit length.
// Where the first dent along the surface pushes every vertex against one normal n (palpate_surface_normal),
// the tilt is that of the surface V - n G: N + (N x grad G) x n, the step along T above turned into
// ((N x T) x n) / |N|.
void palpate_deform_fragment_any(inout vec3 position, inout vec3 normal, vec4 surface, bool use_surface) {
  vec3 n = normal;
  vec3 moved = position;
  for (int i = 0; i < PALPATE_DENT_SLOTS; ++i) {
    if (i >= palpate_dent_count) break;
    vec4 center_depth = palpate_dent_center_depth[i];
    vec4 shape = palpate_dent_shape[i];
    vec3 toward = center_depth.xyz - position;
    float d2 = dot(toward, toward);
    bool pushed = false;
    if (use_surface && i == 0 && palpate_surface_dent != 0) {
      float d = palpate_surface_distance(sqrt(d2), surface, toward);
      d2 = d * d;
      pushed = dot(palpate_surface_normal.xyz, palpate_surface_normal.xyz) > 0.0;
    }
    float kk = dot(toward, toward);
    float nn = dot(n, n);
    float n_k = dot(n, toward);
    float cross2 = nn * kk - n_k * n_k;
    float falloff = exp(-d2 * shape.y);  // G(d) / p
    float step = shape.z * falloff * sqrt(d2 / cross2);
    bool reaches = d2 < shape.x;
    vec3 tilt = toward * nn - n * n_k;
    if (pushed) tilt = cross(cross(n, tilt), palpate_surface_normal.xyz) * inversesqrt(nn);
    moved -= (pushed ? palpate_surface_normal.xyz : normal) * (reaches ? center_depth.w * falloff : 0.0);
    n += tilt * (reaches && cross2 > 1e-12 * kk * nn ? step : 0.0);  // a select: step is not finite there
  }
  position = moved;
  normal = normalize(n);
}
void palpate_deform_fragment(inout vec3 position, inout vec3 normal) {
  palpate_deform_fragment_any(position, normal, vec4(0.0), false);
}
void palpate_deform_fragment(inout vec3 position, inout vec3 normal, vec4 surface) {
  palpate_deform_fragment_any(position, normal, surface, true);
}

// The perturbed unit normal alone (see palpate_deform_fragment).
vec3 palpate_perturb_normal(vec3 normal, vec3 rest_position) {
  palpate_deform_fragment_any(rest_position, normal, vec4(0.0), false);
  return normal;
}
vec3 palpate_perturb_normal(vec3 normal, vec3 rest_position, vec4 surface) {
  palpate_deform_fragment_any(rest_position, normal, surface, true);
  return normal;
}

// Whether a dent reaches `position` (the undeformed one) within its 4 sigma: a shader branches on it to
// skip the dents' work where nothing is dented (on a software rasterizer a block of fragments that all
// branch alike skips it).
bool palpate_reaches(vec3 position) {
  bool reaches = false;
  for (int i = 0; i < PALPATE_DENT_SLOTS; ++i) {
    if (i >= palpate_dent_count) break;
    vec3 offset = position - palpate_dent_center_depth[i].xyz;
    reaches = reaches || dot(offset, offset) < palpate_dent_shape[i].x;
  }
  return reaches;
}
)glsl";

bool is_es(std::string_view shader_source) noexcept {
  const std::size_t at = shader_source.find("#version");
  if (at == std::string_view::npos) return false;
  const std::string_view line = shader_source.substr(at, shader_source.find('\n', at) - at);
  return line.find(" es") != std::string_view::npos;
}

}  // namespace

GlslDialect dialect_of(std::string_view shader_source) noexcept {
  const std::size_t at = shader_source.find("#version");
  if (at == std::string_view::npos) return GlslDialect::uniform_arrays;  // GLSL 1.10
  int version = 0;
  for (std::size_t i = at + 8; i < shader_source.size() && shader_source[i] != '\n'; ++i) {
    const char c = shader_source[i];
    if (c >= '0' && c <= '9') version = version * 10 + (c - '0');
    if (version > 0 && (c < '0' || c > '9')) break;
  }
  return version >= 140 || is_es(shader_source) ? GlslDialect::uniform_block : GlslDialect::uniform_arrays;
}

std::string deform_glsl(GlslDialect dialect, int dent_slots) {
  std::string out = "// palpate: GPU deformation after Luciano, Banerjee, Rizzi 2007 (all in one space)\n";
  out += "#define PALPATE_MAX_DENTS " + std::to_string(max_dents) + "\n";
  out += "#define PALPATE_DENT_SLOTS " + std::to_string(std::clamp(dent_slots, 1, max_dents)) + "\n";
  out.append(dialect == GlslDialect::uniform_block ? uniform_block : uniform_arrays);
  out.append(functions);
  return out;
}

std::string insert_deform_glsl(std::string_view shader_source, int dent_slots) {
  return insert_deform_glsl(shader_source, dent_slots, dialect_of(shader_source));
}

std::string insert_deform_glsl(std::string_view shader_source, int dent_slots, GlslDialect dialect) {
  // After #version and the #extension and #pragma lines that follow it (blank and // comment lines
  // among them kept with them), where GLSL wants those directives: before any declaration.
  std::size_t insert_at = 0;
  const std::size_t version = shader_source.find("#version");
  if (version != std::string_view::npos) {
    std::size_t line = shader_source.find('\n', version);
    insert_at = line == std::string_view::npos ? shader_source.size() : line + 1;
    while (insert_at < shader_source.size()) {
      const std::size_t end = std::min(shader_source.find('\n', insert_at), shader_source.size());
      std::string_view text = shader_source.substr(insert_at, end - insert_at);
      text.remove_prefix(std::min(text.find_first_not_of(" \t\r"), text.size()));
      const bool header = text.empty() || text.starts_with("#extension") || text.starts_with("#pragma") ||
                          text.starts_with("//");
      if (!header) break;
      insert_at = end == shader_source.size() ? end : end + 1;
    }
  }
  std::string out;
  const std::string glsl = deform_glsl(dialect, dent_slots);
  out.reserve(shader_source.size() + glsl.size() + 64);
  out.append(shader_source.substr(0, insert_at));
  if (!out.empty() && out.back() != '\n') out += '\n';
  // GLSL ES has no default float precision in the fragment stage: the snippet brings its own.
  if (is_es(shader_source)) out += "precision highp float;\nprecision highp int;\n";
  out += glsl;
  out.append(shader_source.substr(insert_at));
  return out;
}

DeformBlockData make_deform_block_data(std::span<const Dent> dents) noexcept {
  DeformBlockData data{};
  const std::size_t count = std::min<std::size_t>(dents.size(), max_dents);
  for (std::size_t i = 0; i < count; ++i) {
    const Dent& dent = dents[i];
    const float sigma2 = dent.sigma_mm * dent.sigma_mm;
    const float cutoff = dent_cutoff_sigmas * dent.sigma_mm;
    data.center_depth[i] = glm::vec4(dent.center_mm, dent.depth_mm);
    data.shape[i] = glm::vec4(cutoff * cutoff, 1.0f / (2.0f * sigma2), dent.depth_mm / sigma2, dent.sigma_mm);
  }
  data.count = static_cast<std::int32_t>(count);
  if (count > 0 && dents[0].along_surface) {
    data.surface_dent = 1;
    data.surface_normal = glm::vec4(dents[0].normal, 0.0f);
  }
  return data;
}

}  // namespace palpate::gl
