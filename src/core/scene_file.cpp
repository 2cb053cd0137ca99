// Scene files in TOML through toml++: chosen over JSON because a person edits them by hand
// (comments, no quoting of keys) and because toml++ keeps the line of every value, so each error
// can name the line.
#include "palpate/core/scene_file.hpp"

#include <toml++/toml.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/euler_angles.hpp>
#include <set>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/core/load.hpp"
#include "palpate/core/phantom.hpp"

namespace palpate {
namespace {

int line_of(const toml::node& node) {
  return static_cast<int>(node.source().begin.line);
}

class ObjectReader {
 public:
  ObjectReader(const std::filesystem::path& file, const toml::table& table) : file_(file), table_(table) {
    static const std::set<std::string> known = {
        "name",  "mesh",      "translate", "rotate_deg", "sigma_mm", "stiffness_n_per_mm", "damping_ns_per_m",
        "color", "touchable", "visible",   "falloff"};
    for (const auto& [key, value] : table_) {
      if (!known.contains(std::string(key.str()))) {
        throw Error(file_, line_of(value), "unknown key '" + std::string(key.str()) + "' in [[object]]");
      }
    }
  }

  std::string text(const char* key, bool required) const {
    const toml::node* node = table_.get(key);
    if (!node) {
      if (required) throw Error(file_, line_of(table_), "[[object]] needs '" + std::string(key) + "'");
      return {};
    }
    if (!node->is_string()) throw Error(file_, line_of(*node), std::string("'") + key + "' must be a string");
    return node->value<std::string>().value();
  }

  float number(const char* key, float fallback, float min, float max) const {
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    if (!node->is_number()) throw Error(file_, line_of(*node), std::string("'") + key + "' must be a number");
    const double value = node->value<double>().value();
    if (!(value >= min && value <= max)) {
      throw Error(file_, line_of(*node),
                  std::string("'") + key + "' = " + std::to_string(value) + " is out of range [" +
                      std::to_string(min) + ", " + std::to_string(max) + "]");
    }
    return static_cast<float>(value);
  }

  bool flag(const char* key, bool fallback) const {
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    if (!node->is_boolean())
      throw Error(file_, line_of(*node), std::string("'") + key + "' must be true or false");
    return node->value<bool>().value();
  }

  glm::vec3 vector(const char* key, glm::vec3 fallback, float min, float max) const {
    const toml::node* node = table_.get(key);
    if (!node) return fallback;
    const toml::array* array = node->as_array();
    if (!array || array->size() != 3) {
      throw Error(file_, line_of(*node), std::string("'") + key + "' must be an array of 3 numbers");
    }
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
      const toml::node& item = *array->get(static_cast<std::size_t>(i));
      if (!item.is_number())
        throw Error(file_, line_of(item), std::string("'") + key + "' must hold numbers");
      const double value = item.value<double>().value();
      if (!(value >= min && value <= max)) {
        throw Error(file_, line_of(item),
                    std::string("'") + key + "' component " + std::to_string(value) + " is out of range [" +
                        std::to_string(min) + ", " + std::to_string(max) + "]");
      }
      out[i] = static_cast<float>(value);
    }
    return out;
  }

  Falloff falloff(Falloff fallback) const {
    const toml::node* node = table_.get("falloff");
    if (!node) return fallback;
    const std::optional<std::string> name = node->value<std::string>();
    if (node->is_string() && name == "euclidean") return Falloff::euclidean;
    if (node->is_string() && name == "geodesic") return Falloff::geodesic;
    throw Error(file_, line_of(*node), "'falloff' must be \"euclidean\" or \"geodesic\"");
  }

  int line() const { return line_of(table_); }

 private:
  const std::filesystem::path& file_;
  const toml::table& table_;
};

Mesh mesh_for(const std::filesystem::path& scene_file, const std::string& reference, int line) {
  if (reference == "phantom:brain") return make_brain_phantom();
  if (reference == "phantom:skin") return make_skin_phantom();
  if (reference.starts_with("phantom:")) {
    throw Error(scene_file, line, "unknown phantom '" + reference + "' (phantom:brain or phantom:skin)");
  }
  const std::filesystem::path path = scene_file.parent_path() / reference;
  try {
    return load_mesh(path);
  } catch (const Error& e) {
    throw Error(scene_file, line, "object mesh: " + std::string(e.what()));
  }
}

}  // namespace

Scene load_scene(const std::filesystem::path& file) {
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    if (!std::filesystem::exists(file)) throw Error(file, 0, "cannot open scene file: no such file");
    throw Error(file, static_cast<int>(e.source().begin.line), std::string(e.description()));
  }
  for (const auto& [key, value] : root) {
    if (key.str() != "object")
      throw Error(file, line_of(value), "unknown key '" + std::string(key.str()) + "'");
  }
  const toml::array* objects = root["object"].as_array();
  if (!objects || objects->empty()) throw Error(file, 0, "the scene has no [[object]] tables");

  Scene scene;
  for (const toml::node& node : *objects) {
    const toml::table* table = node.as_table();
    if (!table) throw Error(file, line_of(node), "'object' must be an array of tables ([[object]])");
    const ObjectReader read(file, *table);
    SceneObject object;
    object.name = read.text("name", true);
    const std::string reference = read.text("mesh", true);
    const glm::vec3 translate = read.vector("translate", glm::vec3(0.0f), -1e6f, 1e6f);
    const glm::vec3 rotate = glm::radians(read.vector("rotate_deg", glm::vec3(0.0f), -360.0f, 360.0f));
    object.transform = glm::translate(glm::mat4(1.0f), translate);
    object.transform = glm::rotate(object.transform, rotate.z, {0, 0, 1});
    object.transform = glm::rotate(object.transform, rotate.y, {0, 1, 0});
    object.transform = glm::rotate(object.transform, rotate.x, {1, 0, 0});
    Material& m = object.material;
    m.sigma_mm = read.number("sigma_mm", m.sigma_mm, 0.01f, 1000.0f);
    m.stiffness_n_per_mm = read.number("stiffness_n_per_mm", m.stiffness_n_per_mm, 0.0f, 100.0f);
    m.damping_ns_per_m = read.number("damping_ns_per_m", m.damping_ns_per_m, 0.0f, 1000.0f);
    m.color = read.vector("color", m.color, 0.0f, 1.0f);
    m.touchable = read.flag("touchable", m.touchable);
    m.visible = read.flag("visible", m.visible);
    m.falloff = read.falloff(m.falloff);
    object.mesh = mesh_for(file, reference, read.line());
    if (!reference.starts_with("phantom:")) object.source = file.parent_path() / reference;
    scene.objects.push_back(std::move(object));
  }
  return scene;
}

void save_scene(const Scene& scene, const std::filesystem::path& file) {
  std::string text = "# palpate scene: millimetres, newtons, seconds\n";
  std::error_code error;
  if (!file.parent_path().empty()) std::filesystem::create_directories(file.parent_path(), error);
  for (const SceneObject& object : scene.objects) {
    const glm::mat3 rotation(object.transform);
    const glm::mat3 identity_if_rigid = rotation * glm::transpose(rotation);
    float off = std::abs(glm::determinant(rotation) - 1.0f);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        off = std::max(off, std::abs(identity_if_rigid[c][r] - (c == r ? 1.0f : 0.0f)));
    if (off > 1e-4f) {
      throw Error(file, 0, "object '" + object.name + "': its transform is not a rotation and translation");
    }
    float z = 0.0f, y = 0.0f, x = 0.0f;  // load_scene composes translate * Rz * Ry * Rx
    glm::extractEulerAngleZYX(glm::mat4(rotation), z, y, x);
    const glm::vec3 translate(object.transform[3]);
    const std::filesystem::path mesh_file = file.stem().string() + "_" + object.name + ".ply";
    save_mesh(object.mesh, file.parent_path() / mesh_file);
    const Material& m = object.material;
    char block[1024];
    std::snprintf(block, sizeof block,
                  "\n[[object]]\nname = \"%s\"\nmesh = \"%s\"\ntranslate = [%.6g, %.6g, %.6g]\n"
                  "rotate_deg = [%.6g, %.6g, %.6g]\nsigma_mm = %.6g\nstiffness_n_per_mm = %.6g\n"
                  "damping_ns_per_m = %.6g\ncolor = [%.6g, %.6g, %.6g]\ntouchable = %s\nvisible = %s\n"
                  "falloff = \"%s\"\n",
                  object.name.c_str(), mesh_file.c_str(), translate.x, translate.y, translate.z,
                  glm::degrees(x) + 0.0f, glm::degrees(y) + 0.0f, glm::degrees(z) + 0.0f, m.sigma_mm,
                  m.stiffness_n_per_mm, m.damping_ns_per_m, m.color.r, m.color.g, m.color.b,
                  m.touchable ? "true" : "false", m.visible ? "true" : "false",
                  m.falloff == Falloff::geodesic ? "geodesic" : "euclidean");
    text += block;
  }
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw Error(file, 0, "could not write the scene file");
}

Scene phantom_scene() {
  const auto phantom = [](std::string name, Mesh mesh, Material material) {
    SceneObject object;
    object.name = std::move(name);
    object.mesh = std::move(mesh);
    object.material = material;
    return object;
  };
  Scene scene;
  scene.objects.push_back(phantom("brain", make_brain_phantom(), brain_material));
  scene.objects.push_back(phantom("skin", make_skin_phantom(), skin_material));
  return scene;
}

}  // namespace palpate
