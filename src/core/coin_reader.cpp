#include "core/coin_reader.hpp"

#include <Inventor/SbMatrix.h>
#include <Inventor/SoDB.h>
#include <Inventor/SoInput.h>
#include <Inventor/SoPath.h>
#include <Inventor/SoPrimitiveVertex.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedLineSet.h>
#include <Inventor/VRMLnodes/SoVRMLPointSet.h>
#include <Inventor/VRMLnodes/SoVRMLText.h>
#include <Inventor/VRMLnodes/SoVRMLVertexShape.h>
#include <Inventor/actions/SoCallbackAction.h>
#include <Inventor/elements/SoCreaseAngleElement.h>
#include <Inventor/elements/SoLazyElement.h>
#include <Inventor/elements/SoNormalElement.h>
#include <Inventor/elements/SoShapeHintsElement.h>
#include <Inventor/fields/SoSFBool.h>
#include <Inventor/fields/SoSFFloat.h>
#include <Inventor/nodes/SoAsciiText.h>
#include <Inventor/nodes/SoIndexedLineSet.h>
#include <Inventor/nodes/SoIndexedPointSet.h>
#include <Inventor/nodes/SoLineSet.h>
#include <Inventor/nodes/SoPointSet.h>
#include <Inventor/nodes/SoSeparator.h>
#include <Inventor/nodes/SoShape.h>
#include <Inventor/nodes/SoText2.h>
#include <Inventor/nodes/SoText3.h>
#include <Inventor/nodes/SoVertexProperty.h>
#include <Inventor/nodes/SoVertexShape.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string_view>

#include "core/coin_index_check.hpp"
#include "core/coin_session.hpp"
#include "core/vrml_field_filter.hpp"
#include "core/weld.hpp"
#include "palpate/core/error.hpp"

namespace palpate::detail {
namespace {

// Distinct unknown fields the lenient pass removes before it gives up on a file.
constexpr int kMaxDroppedFields = 64;

void warn(const LoadParams& options, const std::string& message) {
  if (options.on_warning) options.on_warning(message);
}

bool is_any_of(const SoNode* node, std::initializer_list<SoType> types) {
  for (const SoType& type : types) {
    if (node->isOfType(type)) return true;
  }
  return false;
}

// The node type name as the file spells it: Coin names VRML97 nodes "VRMLMaterial" and so on.
std::string file_type_name(const SoNode* node) {
  std::string name = node->getTypeId().getName().getString();
  if (name.rfind("VRML", 0) == 0 && name.size() > 4) name.erase(0, 4);
  return name;
}

glm::vec3 to_glm(const SbVec3f& v) {
  return {v[0], v[1], v[2]};
}

// Collects the triangles of each drawn shape instance into one SceneObject.
class ShapeCollector {
 public:
  explicit ShapeCollector(const std::filesystem::path& file) : file_(file) {}

  void attach(SoCallbackAction& action) {
    action.addPreCallback(SoShape::getClassTypeId(), &ShapeCollector::pre_shape, this);
    action.addTriangleCallback(SoShape::getClassTypeId(), &ShapeCollector::triangle, this);
    action.addPostCallback(SoShape::getClassTypeId(), &ShapeCollector::post_shape, this);
  }

  Scene scene;
  std::optional<Error> error;
  int skipped_text = 0;
  int skipped_lines = 0;

 private:
  struct Current {
    std::string name;
    glm::vec3 material_color{0.8f};
    float crease_angle = 0.0f;
    bool coin_normals = false;  // the file's normals, or Coin's own for primitives
    bool reverse = false;       // clockwise faces or a mirroring transform
    SbMatrix model, normal_matrix;
    TriangleSoup soup;
    glm::vec3 first_color{0.0f};
    bool varied_color = false;
  };

  static SoCallbackAction::Response pre_shape(void* self, SoCallbackAction* action, const SoNode* node) {
    return static_cast<ShapeCollector*>(self)->begin_shape(*action, node);
  }
  static void triangle(void* self, SoCallbackAction* action, const SoPrimitiveVertex* a,
                       const SoPrimitiveVertex* b, const SoPrimitiveVertex* c) {
    static_cast<ShapeCollector*>(self)->add_triangle(*action, *a, *b, *c);
  }
  static SoCallbackAction::Response post_shape(void* self, SoCallbackAction*, const SoNode*) {
    return static_cast<ShapeCollector*>(self)->end_shape();
  }

  SoCallbackAction::Response begin_shape(SoCallbackAction& action, const SoNode* node) {
    if (error) return SoCallbackAction::ABORT;
    active_ = false;
    if (is_any_of(node, {SoText2::getClassTypeId(), SoText3::getClassTypeId(), SoAsciiText::getClassTypeId(),
                         SoVRMLText::getClassTypeId()})) {
      ++skipped_text;  // glyph triangles depend on the fonts found at run time: not a model's geometry
      return SoCallbackAction::PRUNE;
    }
    if (is_any_of(node, {SoLineSet::getClassTypeId(), SoIndexedLineSet::getClassTypeId(),
                         SoPointSet::getClassTypeId(), SoIndexedPointSet::getClassTypeId(),
                         SoVRMLIndexedLineSet::getClassTypeId(), SoVRMLPointSet::getClassTypeId()})) {
      ++skipped_lines;
      return SoCallbackAction::PRUNE;
    }
    SoState* state = action.getState();
    if (std::optional<std::string> bad = check_shape_indices(*node, *state)) {
      error.emplace(file_, 0, file_type_name(node) + " " + shape_name(action, node) + ": " + *bad);
      return SoCallbackAction::ABORT;
    }

    current_ = Current{};
    current_.name = shape_name(action, node);
    current_.material_color = to_glm(SoLazyElement::getDiffuse(state, 0));
    current_.model = action.getModelMatrix();
    current_.normal_matrix = current_.model.inverse().transpose();

    const bool vrml_vertex_shape = node->isOfType(SoVRMLVertexShape::getClassTypeId());
    const bool inventor_vertex_shape = node->isOfType(SoVertexShape::getClassTypeId());
    if (vrml_vertex_shape) {
      current_.coin_normals = static_cast<const SoVRMLVertexShape*>(node)->normal.getValue() != nullptr;
    } else if (inventor_vertex_shape) {
      const SoNode* vp = static_cast<const SoVertexShape*>(node)->vertexProperty.getValue();
      current_.coin_normals = SoNormalElement::getInstance(state)->getNum() > 0 ||
                              (vp && vp->isOfType(SoVertexProperty::getClassTypeId()) &&
                               static_cast<const SoVertexProperty*>(vp)->normal.getNum() > 0);
    } else {
      current_.coin_normals = true;  // primitives (Sphere, Cone, ...): Coin's analytic normals
    }
    if (const SoField* crease = node->getField("creaseAngle");
        crease && crease->isOfType(SoSFFloat::getClassTypeId())) {
      current_.crease_angle = static_cast<const SoSFFloat*>(crease)->getValue();
    } else {
      current_.crease_angle = SoCreaseAngleElement::get(state);
    }
    // Coin hands over a face set's vertices in file order; palpate's front faces are counter-clockwise.
    bool clockwise = false;
    if (vrml_vertex_shape || inventor_vertex_shape) {
      if (const SoField* ccw = node->getField("ccw"); ccw && ccw->isOfType(SoSFBool::getClassTypeId())) {
        clockwise = !static_cast<const SoSFBool*>(ccw)->getValue();
      } else {
        clockwise = SoShapeHintsElement::getVertexOrdering(state) == SoShapeHintsElement::CLOCKWISE;
      }
    }
    current_.reverse = clockwise != (current_.model.det3() < 0.0f);
    active_ = true;
    return SoCallbackAction::CONTINUE;
  }

  void add_triangle(SoCallbackAction& action, const SoPrimitiveVertex& a, const SoPrimitiveVertex& b,
                    const SoPrimitiveVertex& c) {
    if (error || !active_) return;
    SoState* state = action.getState();
    const std::int32_t colors = SoLazyElement::getInstance(state)->getNumDiffuse();
    const SoPrimitiveVertex* corners[3] = {&a, &b, &c};
    if (current_.reverse) std::swap(corners[1], corners[2]);
    for (const SoPrimitiveVertex* v : corners) {
      SbVec3f p;
      current_.model.multVecMatrix(v->getPoint(), p);
      current_.soup.positions_mm.push_back(to_glm(p));
      if (current_.coin_normals) {
        SbVec3f n;
        current_.normal_matrix.multDirMatrix(v->getNormal(), n);
        current_.soup.normals.push_back(to_glm(n));
      }
      const int index = v->getMaterialIndex();
      if (index < 0 || index >= colors) {
        error.emplace(file_, 0,
                      "shape " + current_.name + ": colour index " + std::to_string(index) +
                          " is out of range (" + std::to_string(colors) + " colours)");
        return;
      }
      const glm::vec3 color = to_glm(SoLazyElement::getDiffuse(state, index));
      if (current_.soup.colors.empty()) current_.first_color = color;
      current_.varied_color = current_.varied_color || color != current_.first_color;
      current_.soup.colors.push_back(color);
    }
  }

  SoCallbackAction::Response end_shape() {
    if (error) return SoCallbackAction::ABORT;
    if (!active_ || current_.soup.positions_mm.empty()) return SoCallbackAction::CONTINUE;
    active_ = false;
    for (std::size_t i = 0; i < current_.soup.positions_mm.size(); ++i) {
      const glm::vec3 p = current_.soup.positions_mm[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        error.emplace(file_, 0,
                      "shape " + current_.name + ": triangle " + std::to_string(i / 3) +
                          " has a non-finite coordinate (NaN or Inf) after its transforms");
        return SoCallbackAction::ABORT;
      }
    }
    SceneObject object;
    object.name = current_.name;
    object.source = file_;
    object.material.color = current_.varied_color ? current_.first_color : current_.material_color;
    if (!current_.varied_color) current_.soup.colors.clear();  // one colour: the material's
    object.mesh = mesh_from_soup(current_.soup, current_.crease_angle);
    scene.objects.push_back(std::move(object));
    return SoCallbackAction::CONTINUE;
  }

  // The DEF name of the shape or of its nearest named ancestor, else its type.
  static std::string shape_name(SoCallbackAction& action, const SoNode* node) {
    const SoPath* path = action.getCurPath();
    for (int i = path->getLength() - 1; i >= 0; --i) {
      const SbName name = path->getNode(i)->getName();
      if (name.getLength() > 0) return std::string(name.getString());
    }
    return file_type_name(node);
  }

  const std::filesystem::path& file_;
  Current current_;
  bool active_ = false;
};

struct UnknownField {
  std::string field, node_type;
};

// Coin's words for a field its node type does not define: Unknown field "mirror" in "VRMLMaterial".
std::optional<UnknownField> unknown_field(const std::string& message) {
  constexpr std::string_view opening = "Unknown field \"";
  if (message.rfind(opening, 0) != 0) return std::nullopt;
  const std::size_t field_end = message.find('"', opening.size());
  const std::size_t in = message.find(" in ", field_end);
  if (field_end == std::string::npos || in == std::string::npos) return std::nullopt;
  std::string node_type = message.substr(in + 4);
  std::erase(node_type, '"');
  if (node_type.empty()) return std::nullopt;
  return UnknownField{message.substr(opening.size(), field_end - opening.size()), node_type};
}

// Coin's message, with what it means for palpate where Coin's words alone would mislead.
std::string describe(const CoinSession::ReadError& error, const std::string& text) {
  std::string message = error.message;
  if (message.rfind("Detected non-valid floating point number", 0) == 0) {
    message = "a number is NaN, infinite or out of float range (Coin: " + message + ")";
  }
  const auto lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  if (error.line >= lines) message += " (at the end of the file: is it truncated?)";
  return message;
}

// Reads the scene graph, removing unknown fields and trying again where the options allow it.
SoSeparator* read_scene_graph(CoinSession& coin, std::string text, const std::filesystem::path& file,
                              const LoadParams& options) {
  for (int dropped = 0;; ++dropped) {
    coin.read_errors.clear();
    SoInput input;
    input.setBuffer(text.data(), text.size());
    SoSeparator* root = SoDB::readAll(&input);
    if (root && coin.read_errors.empty()) return root;
    if (root) {
      root->ref();
      root->unref();
    }
    if (coin.read_errors.empty()) throw Error(file, 0, "Coin could not read the file and gave no reason");
    const CoinSession::ReadError first = coin.read_errors.front();
    const std::optional<UnknownField> unknown = unknown_field(first.message);
    if (!unknown || !options.drop_unknown_fields || dropped >= kMaxDroppedFields) {
      throw Error(file, first.line, describe(first, text));
    }
    std::vector<std::string> types{unknown->node_type};
    if (unknown->node_type.rfind("VRML", 0) == 0) types.push_back(unknown->node_type.substr(4));
    const std::size_t removed = remove_vrml_field(text, unknown->field, types);
    if (removed == 0) throw Error(file, first.line, describe(first, text));
    warn(options, file.string() + ":" + std::to_string(first.line) + ": dropped the non-standard field \"" +
                      unknown->field + "\" of " + types.back() + " (" + std::to_string(removed) +
                      (removed == 1 ? " occurrence" : " occurrences") + "), which Coin does not know");
  }
}

}  // namespace

Scene read_coin_model(const std::string& text, const std::filesystem::path& file, const LoadParams& options) {
  CoinSession coin;
  SoSeparator* root = read_scene_graph(coin, text, file, options);
  root->ref();
  ShapeCollector collector(file);
  {
    SoCallbackAction action;
    collector.attach(action);
    action.apply(root);
  }
  root->unref();
  for (const std::string& message : coin.messages) warn(options, file.string() + ": Coin: " + message);
  if (collector.error) throw *collector.error;
  if (collector.skipped_text > 0) {
    warn(options, file.string() + ": skipped " + std::to_string(collector.skipped_text) +
                      " text node(s): text is not model geometry in palpate");
  }
  if (collector.skipped_lines > 0) {
    warn(options, file.string() + ": skipped " + std::to_string(collector.skipped_lines) +
                      " line or point set(s): they have no triangles");
  }
  return std::move(collector.scene);
}

}  // namespace palpate::detail
