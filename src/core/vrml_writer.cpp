#include <Inventor/SoOutput.h>
#include <Inventor/VRMLnodes/SoVRMLAppearance.h>
#include <Inventor/VRMLnodes/SoVRMLColor.h>
#include <Inventor/VRMLnodes/SoVRMLCoordinate.h>
#include <Inventor/VRMLnodes/SoVRMLIndexedFaceSet.h>
#include <Inventor/VRMLnodes/SoVRMLMaterial.h>
#include <Inventor/VRMLnodes/SoVRMLNormal.h>
#include <Inventor/VRMLnodes/SoVRMLShape.h>
#include <Inventor/actions/SoWriteAction.h>

#include <cstdint>
#include <vector>

#include "core/coin_session.hpp"
#include "core/mesh_writers.hpp"
#include "palpate/core/error.hpp"

namespace palpate::detail {
namespace {

std::vector<SbVec3f> to_coin(const std::vector<glm::vec3>& values) {
  std::vector<SbVec3f> out;
  out.reserve(values.size());
  for (const glm::vec3& v : values) out.emplace_back(v.x, v.y, v.z);
  return out;
}

}  // namespace

void write_vrml97(const Mesh& mesh, const std::filesystem::path& file) {
  CoinSession coin;
  auto* coordinates = new SoVRMLCoordinate;
  const std::vector<SbVec3f> points = to_coin(mesh.positions_mm);
  coordinates->point.setValues(0, static_cast<int>(points.size()), points.data());
  auto* normals = new SoVRMLNormal;
  const std::vector<SbVec3f> vectors = to_coin(mesh.normals);
  normals->vector.setValues(0, static_cast<int>(vectors.size()), vectors.data());

  auto* faces = new SoVRMLIndexedFaceSet;
  faces->coord = coordinates;
  faces->normal = normals;
  faces->normalPerVertex = TRUE;
  faces->solid = FALSE;  // open meshes stay visible from behind
  if (!mesh.colors.empty()) {
    auto* colors = new SoVRMLColor;
    std::vector<SbColor> rgb;
    rgb.reserve(mesh.colors.size());
    for (const glm::vec3& c : mesh.colors) rgb.emplace_back(c.r, c.g, c.b);
    colors->color.setValues(0, static_cast<int>(rgb.size()), rgb.data());
    faces->color = colors;
    faces->colorPerVertex = TRUE;
  }
  std::vector<std::int32_t> coord_index;
  coord_index.reserve(mesh.triangle_count() * 4);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int corner = 0; corner < 3; ++corner)
      coord_index.push_back(static_cast<std::int32_t>(mesh.indices[3 * t + corner]));
    coord_index.push_back(-1);
  }
  faces->coordIndex.setValues(0, static_cast<int>(coord_index.size()), coord_index.data());

  auto* appearance = new SoVRMLAppearance;
  appearance->material = new SoVRMLMaterial;
  auto* shape = new SoVRMLShape;
  shape->appearance = appearance;
  shape->geometry = faces;
  shape->ref();

  SoOutput output;
  if (!output.openFile(file.string().c_str())) {
    shape->unref();
    throw Error(file, 0, "cannot open for writing");
  }
  output.setHeaderString("#VRML V2.0 utf8");
  output.setFloatPrecision(9);  // enough digits for a float to read back bit for bit
  SoWriteAction writer(&output);
  writer.apply(shape);
  output.closeFile();
  shape->unref();
}

}  // namespace palpate::detail
