#include "core/coin_index_check.hpp"

#include <Inventor/VRMLnodes/SoVRMLColor.h>
#include <Inventor/VRMLnodes/SoVRMLCoordinate.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedFaceSet.h>
#include <Inventor/VRMLnodes/SoVRMLNormal.h>
#include <Inventor/VRMLnodes/SoVRMLTextureCoordinate.h>
#include <Inventor/elements/SoCoordinateElement.h>
#include <Inventor/elements/SoMaterialBindingElement.h>
#include <Inventor/elements/SoNormalBindingElement.h>
#include <Inventor/elements/SoNormalElement.h>
#include <Inventor/nodes/SoFaceSet.h>
#include <Inventor/nodes/SoIndexedFaceSet.h>
#include <Inventor/nodes/SoIndexedTriangleStripSet.h>
#include <Inventor/nodes/SoQuadMesh.h>
#include <Inventor/nodes/SoTriangleStripSet.h>
#include <Inventor/nodes/SoVertexProperty.h>

#include <algorithm>
#include <cstdint>

namespace palpate::detail {
namespace {

using Result = std::optional<std::string>;

std::string entries(std::int64_t n, const char* what) {
  return std::to_string(n) + " " + what;
}

// Every entry of `list` must be -1 (a polygon's end, where `separators`) or an index below `count`.
Result check_range(const SoMFInt32& list, std::int32_t count, const char* list_name, const char* target,
                   bool separators) {
  const std::int32_t* values = list.getValues(0);
  for (int i = 0; i < list.getNum(); ++i) {
    const std::int32_t v = values[i];
    if ((v == -1 && separators) || (v >= 0 && v < count)) continue;
    return std::string(list_name) + "[" + std::to_string(i) + "] is " + std::to_string(v) + ", but " +
           target + " has " + entries(count, "entries") +
           (separators ? " (valid: 0.." + std::to_string(count - 1) + " or -1)" : "");
  }
  return std::nullopt;
}

std::int32_t max_index(const SoMFInt32& list) {
  std::int32_t m = -1;
  for (int i = 0; i < list.getNum(); ++i) m = std::max(m, list[i]);
  return m;
}

int polygon_count(const SoMFInt32& coord_index) {
  int polygons = 0;
  bool open = false;
  for (int i = 0; i < coord_index.getNum(); ++i) {
    if (coord_index[i] < 0) {
      polygons += open ? 1 : 0;
      open = false;
    } else {
      open = true;
    }
  }
  return polygons + (open ? 1 : 0);
}

// VRML97: colours and normals are per vertex (through their own index list, or through coordIndex
// when it is empty) or per face (through their index list, or in face order).
Result check_vrml_attribute(const SoVRMLIndexedFaceSet& ifs, std::int32_t count, const SoMFInt32& index,
                            bool per_vertex, const char* index_name, const char* target) {
  const int polygons = polygon_count(ifs.coordIndex);
  if (per_vertex) {
    if (index.getNum() == 0) {
      const std::int32_t needed = max_index(ifs.coordIndex) + 1;
      if (needed > count) {
        return std::string("coordIndex uses ") + target + " " + std::to_string(needed - 1) + " (" +
               index_name + " is empty), but " + target + " has " + entries(count, "entries");
      }
      return std::nullopt;
    }
    if (index.getNum() < ifs.coordIndex.getNum()) {
      return std::string(index_name) + " has " + entries(index.getNum(), "entries") +
             ", fewer than coordIndex's " + std::to_string(ifs.coordIndex.getNum());
    }
    return check_range(index, count, index_name, target, true);
  }
  if (index.getNum() == 0) {
    if (count < polygons) {
      return std::string(target) + " has " + entries(count, "entries") + " for " + entries(polygons, "faces");
    }
    return std::nullopt;
  }
  if (index.getNum() < polygons) {
    return std::string(index_name) + " has " + entries(index.getNum(), "entries") + " for " +
           entries(polygons, "faces");
  }
  return check_range(index, count, index_name, target, false);
}

Result check_vrml_face_set(const SoVRMLIndexedFaceSet& ifs) {
  const SoNode* coord = ifs.coord.getValue();
  if (!coord || !coord->isOfType(SoVRMLCoordinate::getClassTypeId())) return std::nullopt;  // draws nothing
  const std::int32_t points = static_cast<const SoVRMLCoordinate*>(coord)->point.getNum();
  if (Result r = check_range(ifs.coordIndex, points, "coordIndex", "Coordinate.point", true)) return r;
  if (const SoNode* n = ifs.normal.getValue(); n && n->isOfType(SoVRMLNormal::getClassTypeId())) {
    const std::int32_t count = static_cast<const SoVRMLNormal*>(n)->vector.getNum();
    if (Result r = check_vrml_attribute(ifs, count, ifs.normalIndex, ifs.normalPerVertex.getValue(),
                                        "normalIndex", "Normal.vector")) {
      return r;
    }
  }
  if (const SoNode* c = ifs.color.getValue(); c && c->isOfType(SoVRMLColor::getClassTypeId())) {
    const std::int32_t count = static_cast<const SoVRMLColor*>(c)->color.getNum();
    if (Result r = check_vrml_attribute(ifs, count, ifs.colorIndex, ifs.colorPerVertex.getValue(),
                                        "colorIndex", "Color.color")) {
      return r;
    }
  }
  if (const SoNode* t = ifs.texCoord.getValue();
      t && t->isOfType(SoVRMLTextureCoordinate::getClassTypeId())) {
    const std::int32_t count = static_cast<const SoVRMLTextureCoordinate*>(t)->point.getNum();
    if (Result r = check_vrml_attribute(ifs, count, ifs.texCoordIndex, true, "texCoordIndex",
                                        "TextureCoordinate.point")) {
      return r;
    }
  }
  return std::nullopt;
}

// Inventor / VRML 1.0 shapes take coordinates and normals from the traversal state, or from their
// own vertexProperty node.
struct InventorCounts {
  std::int32_t coordinates = 0;
  std::int32_t normals = 0;
  int normal_binding = SoNormalBindingElement::DEFAULT;
};

InventorCounts inventor_counts(const SoVertexShape& shape, SoState& state) {
  InventorCounts counts;
  counts.coordinates = SoCoordinateElement::getInstance(&state)->getNum();
  counts.normals = SoNormalElement::getInstance(&state)->getNum();
  counts.normal_binding = SoNormalBindingElement::get(&state);
  if (const SoNode* vp = shape.vertexProperty.getValue();
      vp && vp->isOfType(SoVertexProperty::getClassTypeId())) {
    const auto* property = static_cast<const SoVertexProperty*>(vp);
    if (property->vertex.getNum() > 0) counts.coordinates = property->vertex.getNum();
    if (property->normal.getNum() > 0) {
      counts.normals = property->normal.getNum();
      counts.normal_binding = property->normalBinding.getValue();
    }
  }
  return counts;
}

bool is_default_index(const SoMFInt32& list) {
  return list.getNum() == 0 || (list.getNum() == 1 && list[0] == -1);
}

Result check_inventor_indexed(const SoIndexedShape& shape, SoState& state, bool faces) {
  const InventorCounts counts = inventor_counts(shape, state);
  if (Result r =
          check_range(shape.coordIndex, counts.coordinates, "coordIndex", "the current Coordinate3", true))
    return r;
  if (counts.normals > 0 && counts.normal_binding != SoNormalBindingElement::OVERALL) {
    const bool indexed = counts.normal_binding == SoNormalBindingElement::PER_VERTEX_INDEXED ||
                         counts.normal_binding == SoNormalBindingElement::PER_FACE_INDEXED ||
                         counts.normal_binding == SoNormalBindingElement::PER_PART_INDEXED;
    if (indexed && !is_default_index(shape.normalIndex)) {
      if (Result r =
              check_range(shape.normalIndex, counts.normals, "normalIndex", "the current Normal", true))
        return r;
      if (counts.normal_binding == SoNormalBindingElement::PER_VERTEX_INDEXED &&
          shape.normalIndex.getNum() < shape.coordIndex.getNum()) {
        return "normalIndex has " + entries(shape.normalIndex.getNum(), "entries") +
               ", fewer than coordIndex's " + std::to_string(shape.coordIndex.getNum());
      }
    } else if (counts.normal_binding == SoNormalBindingElement::PER_VERTEX_INDEXED) {
      if (max_index(shape.coordIndex) >= counts.normals) {
        return "coordIndex uses normal " + std::to_string(max_index(shape.coordIndex)) +
               " (normalIndex is empty), but the current Normal has " + entries(counts.normals, "vectors");
      }
    } else if (faces && counts.normal_binding == SoNormalBindingElement::PER_FACE &&
               counts.normals < polygon_count(shape.coordIndex)) {
      return "the current Normal has " + entries(counts.normals, "vectors") + " for " +
             entries(polygon_count(shape.coordIndex), "faces") + " (NormalBinding PER_FACE)";
    }
  }
  const int material_binding = SoMaterialBindingElement::get(&state);
  if (!is_default_index(shape.materialIndex) &&
      material_binding == SoMaterialBindingElement::PER_VERTEX_INDEXED &&
      shape.materialIndex.getNum() < shape.coordIndex.getNum()) {
    return "materialIndex has " + entries(shape.materialIndex.getNum(), "entries") +
           ", fewer than coordIndex's " + std::to_string(shape.coordIndex.getNum());
  }
  return std::nullopt;
}

Result check_inventor_sequential(const SoNonIndexedShape& shape, const SoMFInt32* vertices_per_part,
                                 std::int32_t fixed_total, SoState& state) {
  const InventorCounts counts = inventor_counts(shape, state);
  std::int64_t total = fixed_total;
  if (vertices_per_part) {
    for (int i = 0; i < vertices_per_part->getNum(); ++i) {
      const std::int32_t n = (*vertices_per_part)[i];
      if (n == -1) return std::nullopt;  // "the rest of the coordinates": always in range
      if (n < 0) return "numVertices[" + std::to_string(i) + "] is " + std::to_string(n);
      total += n;
    }
  }
  const std::int64_t needed = shape.startIndex.getValue() + total;
  if (shape.startIndex.getValue() < 0 || needed > counts.coordinates) {
    return "startIndex " + std::to_string(shape.startIndex.getValue()) + " + " + entries(total, "vertices") +
           " needs " + std::to_string(needed) + " coordinates, but the current Coordinate3 has " +
           std::to_string(counts.coordinates);
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> check_shape_indices(const SoNode& shape, SoState& state) {
  if (shape.isOfType(SoVRMLIndexedFaceSet::getClassTypeId())) {
    return check_vrml_face_set(static_cast<const SoVRMLIndexedFaceSet&>(shape));
  }
  if (shape.isOfType(SoIndexedFaceSet::getClassTypeId())) {
    return check_inventor_indexed(static_cast<const SoIndexedShape&>(shape), state, true);
  }
  if (shape.isOfType(SoIndexedTriangleStripSet::getClassTypeId())) {
    return check_inventor_indexed(static_cast<const SoIndexedShape&>(shape), state, false);
  }
  if (shape.isOfType(SoFaceSet::getClassTypeId())) {
    const auto& set = static_cast<const SoFaceSet&>(shape);
    return check_inventor_sequential(set, &set.numVertices, 0, state);
  }
  if (shape.isOfType(SoTriangleStripSet::getClassTypeId())) {
    const auto& set = static_cast<const SoTriangleStripSet&>(shape);
    return check_inventor_sequential(set, &set.numVertices, 0, state);
  }
  if (shape.isOfType(SoQuadMesh::getClassTypeId())) {
    const auto& mesh = static_cast<const SoQuadMesh&>(shape);
    const std::int32_t rows = mesh.verticesPerColumn.getValue(), columns = mesh.verticesPerRow.getValue();
    if (rows < 0 || columns < 0) return std::string("QuadMesh has a negative vertex count");
    return check_inventor_sequential(mesh, nullptr, rows * columns, state);
  }
  return std::nullopt;
}

}  // namespace palpate::detail
