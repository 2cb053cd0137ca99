#pragma once
// The GLSL of palpate's Renderer: one vertex and one fragment source, specialised by #defines, so that
// the plain and the deforming programs differ only by the deformation itself.
#include <string>

namespace palpate::gl {

struct ShaderVariant {
  int dent_slots = 0;          // > 0: PALPATE_DEFORM, palpate_displace and palpate_perturb_normal over
                               // this many dent slots (PALPATE_DENT_SLOTS)
  bool normals = false;        // PALPATE_NORMALS: output the shading normal (debug), not lit colour
  bool vertex_colors = false;  // PALPATE_VERTEX_COLORS: colour from attribute 2, not a uniform
};

std::string render_vertex_shader(ShaderVariant variant);
std::string render_fragment_shader(ShaderVariant variant);

// The occlusion queries' program (occlusion_proxy.hpp): depth only, no colour, each proxy vertex
// padded by the uniform `pad`.
std::string occlusion_proxy_vertex_shader();
std::string occlusion_proxy_fragment_shader();

}  // namespace palpate::gl
