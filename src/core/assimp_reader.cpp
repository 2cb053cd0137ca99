#include "core/assimp_reader.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <utility>

#include "core/weld.hpp"
#include "palpate/core/error.hpp"

// Debian's assimp 5.2 is built with its internal assertions on (ASSIMP_BUILD_DEBUG), and a failed
// one aborts the process: a PLY file cut short trips one in the triangulation step. This definition
// takes the place of assimp's own (a symbol of the executable wins when the dynamic linker binds
// libassimp's call) and throws instead; Importer::ReadFile catches the exception and reports it as
// an import error. (Where palpate is linked into a shared library instead, assimp's own handler
// stays in place.)
namespace Assimp {
void aiAssertViolation(const char* expression, const char* /*file*/, int /*line*/) {
  throw std::runtime_error(std::string("assimp's internal check \"") + expression +
                           "\" failed (the file is probably truncated or malformed)");
}
}  // namespace Assimp

namespace palpate::detail {
namespace {

glm::vec3 transform_point(const aiMatrix4x4& m, const aiVector3D& v) {
  const aiVector3D p = m * v;
  return {p.x, p.y, p.z};
}

struct Collector {
  const AssimpInput& input;
  const aiScene& scene;
  Scene result;
  std::size_t skipped_faces = 0;

  void visit(const aiNode& node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 model = parent * node.mTransformation;
    aiMatrix3x3 normal_matrix(model);
    normal_matrix.Inverse().Transpose();
    const bool mirrored = aiMatrix3x3(model).Determinant() < 0.0f;
    for (unsigned i = 0; i < node.mNumMeshes; ++i)
      add_mesh(*scene.mMeshes[node.mMeshes[i]], node, model, normal_matrix, mirrored);
    for (unsigned i = 0; i < node.mNumChildren; ++i) visit(*node.mChildren[i], model);
  }

  void add_mesh(const aiMesh& in, const aiNode& node, const aiMatrix4x4& model,
                const aiMatrix3x3& normal_matrix, bool mirrored) {
    if (!(in.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return;
    SceneObject object;
    object.name = in.mName.length > 0 ? in.mName.C_Str() : node.mName.C_Str();
    object.source = input.file;
    if (in.mMaterialIndex < scene.mNumMaterials) {
      aiColor4D diffuse;
      if (scene.mMaterials[in.mMaterialIndex]->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS) {
        object.material.color = {diffuse.r, diffuse.g, diffuse.b};
      }
    }
    Mesh& mesh = object.mesh;
    mesh.positions_mm.reserve(in.mNumVertices);
    for (unsigned v = 0; v < in.mNumVertices; ++v)
      mesh.positions_mm.push_back(transform_point(model, in.mVertices[v]));
    if (in.HasNormals()) {
      mesh.normals.reserve(in.mNumVertices);
      for (unsigned v = 0; v < in.mNumVertices; ++v) {
        aiVector3D n = normal_matrix * in.mNormals[v];
        const float length = n.Length();
        mesh.normals.push_back(length > 0.0f ? glm::vec3(n.x, n.y, n.z) / length : glm::vec3(0.0f));
      }
    }
    if (in.HasVertexColors(0)) {
      mesh.colors.reserve(in.mNumVertices);
      for (unsigned v = 0; v < in.mNumVertices; ++v)
        mesh.colors.emplace_back(in.mColors[0][v].r, in.mColors[0][v].g, in.mColors[0][v].b);
    }
    mesh.indices.reserve(std::size_t{in.mNumFaces} * 3);
    for (unsigned f = 0; f < in.mNumFaces; ++f) {
      const aiFace& face = in.mFaces[f];
      if (face.mNumIndices != 3) {
        ++skipped_faces;
        continue;
      }
      mesh.indices.insert(mesh.indices.end(),
                          {face.mIndices[0], mirrored ? face.mIndices[2] : face.mIndices[1],
                           mirrored ? face.mIndices[1] : face.mIndices[2]});
    }
    for (std::size_t v = 0; v < mesh.positions_mm.size(); ++v) {
      const glm::vec3 p = mesh.positions_mm[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw Error(input.file, 0,
                    "mesh '" + object.name + "': vertex " + std::to_string(v) +
                        " has a non-finite coordinate (NaN or Inf)");
      }
    }
    if (input.weld_positions) {
      weld_positions(mesh);
    } else {
      weld_identical(mesh);
    }
    if (mesh.normals.empty()) {
      compute_vertex_normals(mesh);
    } else if (std::any_of(mesh.normals.begin(), mesh.normals.end(),
                           [](glm::vec3 n) { return n == glm::vec3(0.0f); })) {
      // Zero normals in the file (or assimp's) get the area-weighted ones.
      Mesh computed = mesh;
      compute_vertex_normals(computed);
      for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
        if (mesh.normals[v] == glm::vec3(0.0f)) mesh.normals[v] = computed.normals[v];
      }
    }
    if (mesh.indices.empty()) return;
    result.objects.push_back(std::move(object));
  }
};

}  // namespace

Scene read_assimp_model(const AssimpInput& input, const LoadParams& options) {
  Assimp::Importer importer;
  // Line and point primitives are split off by SortByPType and dropped: palpate draws triangles.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // No aiProcess_JoinIdenticalVertices: palpate welds after import (weld.hpp), exactly and in
  // linear time, where assimp's step took most of a large PLY's load.
  const unsigned flags = aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
  const aiScene* scene = input.memory
                             ? importer.ReadFileFromMemory(input.memory->data(), input.memory->size(), flags,
                                                           input.format_hint.c_str())
                             : importer.ReadFile(input.file.string(), flags);
  if (!scene) {
    std::string reason = importer.GetErrorString();
    while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
    if (reason.find("mNumMeshes is 0") != std::string::npos) {
      // assimp's validation words for a file it parsed but found no meshes in.
      throw Error(
          input.file, 0,
          "assimp found no triangle meshes in it (its importers skip nodes they do not support; the X3D "
          "importer also drops everything inside Collision nodes)");
    }
    throw Error(input.file, 0,
                "assimp could not read it: " + (reason.empty() ? std::string("no reason given") : reason));
  }
  if (!scene->mRootNode) throw Error(input.file, 0, "assimp returned a scene without nodes");
  Collector collector{input, *scene, {}};
  collector.visit(*scene->mRootNode, aiMatrix4x4());
  if (collector.skipped_faces > 0 && options.on_warning) {
    options.on_warning(input.file.string() + ": skipped " + std::to_string(collector.skipped_faces) +
                       " faces that assimp did not triangulate");
  }
  return std::move(collector.result);
}

}  // namespace palpate::detail
