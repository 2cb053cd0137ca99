#include "palpate/coin/deform_shader.hpp"

#include <Inventor/SoDB.h>
#include <Inventor/nodes/SoFragmentShader.h>
#include <Inventor/nodes/SoShaderParameter.h>
#include <Inventor/nodes/SoShaderProgram.h>
#include <Inventor/nodes/SoVertexShader.h>

#include <string>

#include "palpate/core/error.hpp"
#include "palpate/gl/deform_glsl.hpp"

namespace palpate::coin {
namespace {

constexpr int max_lights = 8;  // OpenGL's fixed-function lights

// OpenGL 2.1's lighting equation (section 2.14.1) with an infinitely distant viewer, as Coin leaves it:
// emission, the light model's ambient, and per light its ambient, diffuse (the vertex colour, as with
// Coin's colour material) and Blinn specular, attenuated and within spot cones. Eye space.
constexpr const char* lighting = R"glsl(
vec3 palpate_light(vec3 eye, vec3 n, vec3 diffuse_colour) {
  vec3 colour = gl_FrontMaterial.emission.rgb + gl_FrontMaterial.ambient.rgb * gl_LightModel.ambient.rgb;
  for (int i = 0; i < PALPATE_LIGHTS; ++i) {
    vec4 light = gl_LightSource[i].position;
    vec3 to_light = light.w == 0.0 ? normalize(light.xyz) : normalize(light.xyz - eye);
    float factor = 1.0;
    if (light.w != 0.0) {
      float d = length(light.xyz - eye);
      factor = 1.0 / (gl_LightSource[i].constantAttenuation + gl_LightSource[i].linearAttenuation * d +
                       gl_LightSource[i].quadraticAttenuation * d * d);
      if (gl_LightSource[i].spotCutoff <= 90.0) {
        float c = dot(-to_light, normalize(gl_LightSource[i].spotDirection));
        factor *= c < gl_LightSource[i].spotCosCutoff ? 0.0 : pow(max(c, 0.0), gl_LightSource[i].spotExponent);
      }
    }
    float diffuse = max(dot(n, to_light), 0.0);
    float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(to_light + vec3(0.0, 0.0, 1.0))), 0.0),
                                         gl_FrontMaterial.shininess) : 0.0;
    colour += factor * (gl_FrontMaterial.ambient.rgb * gl_LightSource[i].ambient.rgb +
                        diffuse * diffuse_colour * gl_LightSource[i].diffuse.rgb +
                        specular * gl_FrontMaterial.specular.rgb * gl_LightSource[i].specular.rgb);
  }
  return colour;
}
)glsl";

// The deformation in the shapes' own coordinates (gl_Vertex); lighting in eye space. gl_Position is
// ftransform() plus the displacement taken to clip space, so that away from the dents it is the fixed
// function's own to the bit. Per vertex (Coin's own shading), each vertex is lit with the true normal
// of the deformed surface there. Per fragment, the vertex colour serves the fragments no dent reaches
// and the others are lit with the tilted normal of the fragment itself.
constexpr const char* vertex_main = R"glsl(
varying vec3 palpate_rest;  // the shapes' coordinates
varying vec3 palpate_normal;
varying vec3 palpate_vertex_lit;
void main() {
  palpate_rest = gl_Vertex.xyz / gl_Vertex.w;
  palpate_normal = normalize(gl_Normal);
  vec3 moved = palpate_displace(palpate_rest, palpate_normal);
  gl_Position = ftransform() + gl_ModelViewProjectionMatrix * vec4(moved - palpate_rest, 0.0);
  vec3 position = palpate_rest;
  vec3 normal = palpate_normal;
#if !PALPATE_PER_FRAGMENT
  palpate_deform_fragment(position, normal);
#endif
  palpate_vertex_lit = palpate_light((gl_ModelViewMatrix * vec4(position, 1.0)).xyz,
                                     normalize(gl_NormalMatrix * normal), gl_Color.rgb);
  gl_FrontColor = gl_Color;  // Coin sends the diffuse colour (SoMaterial or per vertex) as glColor
}
)glsl";

constexpr const char* fragment_main = R"glsl(
varying vec3 palpate_rest;
varying vec3 palpate_normal;
varying vec3 palpate_vertex_lit;
void main() {
  vec3 colour = palpate_vertex_lit;
#if PALPATE_PER_FRAGMENT
  if (palpate_reaches(palpate_rest)) {
    vec3 position = palpate_rest;
    vec3 normal = palpate_normal;
    palpate_deform_fragment(position, normal);
    colour = palpate_light((gl_ModelViewMatrix * vec4(position, 1.0)).xyz, normalize(gl_NormalMatrix * normal),
                           gl_Color.rgb);
  }
#endif
  gl_FragColor = vec4(colour, gl_Color.a);
}
)glsl";

}  // namespace

struct DeformShader::State {
  SoShaderProgram* program = nullptr;
  SoShaderParameterArray4f* center_depth = nullptr;
  SoShaderParameterArray4f* shape = nullptr;
  SoShaderParameter1i* count = nullptr;
  int slots = 1;
};

DeformShader::DeformShader(DeformShaderParams params) : state_(std::make_unique<State>()) {
  if (params.dent_slots < 1 || params.dent_slots > max_dents)
    throw Error("DeformShader: dent_slots must be 1.." + std::to_string(max_dents));
  if (params.lights < 1 || params.lights > max_lights)
    throw Error("DeformShader: lights must be 1.." + std::to_string(max_lights));
  if (!SoDB::isInitialized()) SoDB::init();
  state_->slots = params.dent_slots;
  const std::string header = "#version 120\n#define PALPATE_LIGHTS " + std::to_string(params.lights) +
                             "\n#define PALPATE_PER_FRAGMENT " + (params.per_fragment ? "1" : "0") + "\n" +
                             gl::deform_glsl(gl::GlslDialect::uniform_arrays, params.dent_slots) + lighting;

  auto* vertex = new SoVertexShader;
  vertex->sourceType = SoShaderObject::GLSL_PROGRAM;
  vertex->sourceProgram = (header + vertex_main).c_str();
  auto* fragment = new SoFragmentShader;
  fragment->sourceType = SoShaderObject::GLSL_PROGRAM;
  fragment->sourceProgram = (header + fragment_main).c_str();

  // Parameters on the vertex shader reach the fragment shader too (one program).
  state_->center_depth = new SoShaderParameterArray4f;
  state_->center_depth->name = "palpate_dent_center_depth";
  state_->shape = new SoShaderParameterArray4f;
  state_->shape->name = "palpate_dent_shape";
  state_->count = new SoShaderParameter1i;
  state_->count->name = "palpate_dent_count";
  state_->count->value = 0;
  vertex->parameter.set1Value(0, state_->center_depth);
  vertex->parameter.set1Value(1, state_->shape);
  vertex->parameter.set1Value(2, state_->count);
  set({});

  state_->program = new SoShaderProgram;
  state_->program->ref();
  state_->program->shaderObject.set1Value(0, vertex);
  state_->program->shaderObject.set1Value(1, fragment);
}

DeformShader::~DeformShader() {
  state_->program->unref();
}

SoShaderProgram* DeformShader::node() const noexcept {
  return state_->program;
}

int DeformShader::set(std::span<const Dent> dents) {
  const gl::DeformBlockData data = gl::make_deform_block_data(
      dents.first(std::min<std::size_t>(dents.size(), std::size_t(state_->slots))));
  SbVec4f center_depth[max_dents], shape[max_dents];
  for (int i = 0; i < state_->slots; ++i) {
    const glm::vec4 c = data.center_depth[i], s = data.shape[i];
    center_depth[i].setValue(c.x, c.y, c.z, c.w);
    shape[i].setValue(s.x, s.y, s.z, s.w);
  }
  state_->center_depth->value.setValues(0, state_->slots, center_depth);
  state_->shape->value.setValues(0, state_->slots, shape);
  state_->count->value = data.count;
  return int(dents.size()) - data.count;
}

}  // namespace palpate::coin
