#include "palpate/gl/deform_glsl.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "palpate/core/error.hpp"

namespace palpate::gl {
namespace {

// The formulas of palpate/core/deform.cpp, written for SIMD shader cores: squared distances are
// compared before anything is computed, and the normal is tilted without trigonometry (see below).
constexpr std::string_view source = R"glsl(
// palpate: GPU deformation after Luciano, Banerjee, Rizzi 2007. All positions in world mm.
#define PALPATE_MAX_DENTS 8
layout(std140) uniform PalpateDeform {
  vec4 palpate_dent_center_depth[PALPATE_MAX_DENTS];  // xyz contact point c, w penetration p
  vec4 palpate_dent_shape[PALPATE_MAX_DENTS];         // x (4 sigma)^2, y 1/(2 sigma^2), z p/sigma^2, w sigma
  int palpate_dent_count;
};
// The loops below run over a compile-time number of slots so that the block is read at constant
// offsets (a software rasterizer gathers lane by lane from a dynamic index). Define it, before this
// source, to the most dents a shader must serve: each slot costs a full dent on SIMD cores without
// branches, and dents past it are ignored.
#ifndef PALPATE_DENT_SLOTS
#define PALPATE_DENT_SLOTS PALPATE_MAX_DENTS
#endif

// V' = V - N * sum G(d), G(d) = p exp(-d^2 / 2 sigma^2), d = |V - c|; a dent is skipped beyond 4 sigma.
// world_normal must be of unit length: at d = 0 the surface moves by exactly p, to the tool tip.
vec3 palpate_displace(vec3 world_position, vec3 world_normal) {
  float g = 0.0;
  for (int i = 0; i < PALPATE_DENT_SLOTS; ++i) {
    if (i >= palpate_dent_count) break;
    vec4 center_depth = palpate_dent_center_depth[i];
    vec3 offset = world_position - center_depth.xyz;
    float d2 = dot(offset, offset);
    g += d2 < palpate_dent_shape[i].x ? center_depth.w * exp(-d2 * palpate_dent_shape[i].y) : 0.0;
  }
  return world_position - world_normal * g;
}

// The fragment stage: from the undeformed world position and normal interpolated to this fragment,
// the displaced position V - N sum G(d), evaluated here (N as interpolated: of about unit length), and
// the paper's per-fragment normal: N rotated about W = N x VC by theta = atan(-G'(d)) toward the contact
// point, G'(d) = -p d / sigma^2 exp(-d^2 / 2 sigma^2), one dent after the other.
// Without trigonometry: with T = (W x N) / |W x N|, the unit tangent toward c, the rotated normal is
// cos(theta) (N + tan(theta) T); its direction is that of N + tan(theta) |N| T for any length of N, so
// the scale is dropped and the result normalised once. W x N = VC |N|^2 - N (N.VC) has the length
// |N| |N x VC|, so the step along it is tan(theta) / |N x VC| = (p / sigma^2) exp(-d^2 / 2 sigma^2)
// sqrt(d^2 / |N x VC|^2), with |N x VC|^2 = |N|^2 d^2 - (N.VC)^2.
// d is measured from the undeformed position, as in palpate_displace. No tilt beyond 4 sigma, nor where
// d = 0 or N is parallel to VC (|N x VC|^2 <= 1e-12 d^2 |N|^2, as the CPU twin). The normal comes out
// of unit length.
void palpate_deform_fragment(inout vec3 world_position, inout vec3 world_normal) {
  vec3 n = world_normal;
  float g = 0.0;
  for (int i = 0; i < PALPATE_DENT_SLOTS; ++i) {
    if (i >= palpate_dent_count) break;
    vec4 center_depth = palpate_dent_center_depth[i];
    vec4 shape = palpate_dent_shape[i];
    vec3 vc = center_depth.xyz - world_position;
    float d2 = dot(vc, vc);
    float nn = dot(n, n);
    float n_vc = dot(n, vc);
    float cross2 = nn * d2 - n_vc * n_vc;
    float falloff = exp(-d2 * shape.y);  // G(d) / p
    float step = shape.z * falloff * sqrt(d2 / cross2);
    bool reaches = d2 < shape.x;
    g += reaches ? center_depth.w * falloff : 0.0;
    n += (vc * nn - n * n_vc) * (reaches && cross2 > 1e-12 * d2 * nn ? step : 0.0);  // a select: step is
  }                                                                                 // not finite there
  world_position -= world_normal * g;
  world_normal = normalize(n);
}

// The perturbed unit normal alone (see palpate_deform_fragment).
vec3 palpate_perturb_normal(vec3 world_normal, vec3 rest_world_position) {
  palpate_deform_fragment(rest_world_position, world_normal);
  return world_normal;
}
)glsl";

}  // namespace

std::string_view deform_glsl() noexcept {
  return source;
}

std::string insert_deform_glsl(std::string_view shader_source, int dent_slots) {
  std::size_t insert_at = 0;
  const std::size_t version = shader_source.find("#version");
  if (version != std::string_view::npos) {
    const std::size_t line_end = shader_source.find('\n', version);
    insert_at = line_end == std::string_view::npos ? shader_source.size() : line_end + 1;
  }
  std::string out;
  out.reserve(shader_source.size() + source.size() + 1);
  out.append(shader_source.substr(0, insert_at));
  if (insert_at > 0 && out.back() != '\n') out += '\n';
  out += "#define PALPATE_DENT_SLOTS " + std::to_string(std::clamp(dent_slots, 1, max_dents)) + "\n";
  out.append(source);
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
  return data;
}

DeformBlock::DeformBlock(GLuint binding) : binding_(binding) {
  glCreateBuffers(1, &buffer_);
  const DeformBlockData empty{};
  glNamedBufferData(buffer_, sizeof(DeformBlockData), &empty, GL_DYNAMIC_DRAW);
}

DeformBlock::~DeformBlock() {
  if (buffer_) glDeleteBuffers(1, &buffer_);
}

DeformBlock::DeformBlock(DeformBlock&& other) noexcept
    : buffer_(std::exchange(other.buffer_, 0)), binding_(other.binding_) {}

DeformBlock& DeformBlock::operator=(DeformBlock&& other) noexcept {
  if (this != &other) {
    if (buffer_) glDeleteBuffers(1, &buffer_);
    buffer_ = std::exchange(other.buffer_, 0);
    binding_ = other.binding_;
  }
  return *this;
}

void DeformBlock::attach(GLuint program) const {
  const GLuint index = glGetUniformBlockIndex(program, deform_block_name);
  if (index == GL_INVALID_INDEX) {
    throw Error("program " + std::to_string(program) + " has no active uniform block " + deform_block_name +
                ": include deform_glsl() and call palpate_displace or palpate_perturb_normal");
  }
  glUniformBlockBinding(program, index, binding_);
}

int DeformBlock::update(std::span<const Dent> dents) noexcept {
  const DeformBlockData data = make_deform_block_data(dents);
  glNamedBufferSubData(buffer_, 0, sizeof(DeformBlockData), &data);
  return static_cast<int>(dents.size()) - data.count;
}

void DeformBlock::bind() const noexcept {
  glBindBufferBase(GL_UNIFORM_BUFFER, binding_, buffer_);
}

}  // namespace palpate::gl
