#pragma once
// Reading and writing model files. Setup code: allocates, throws palpate::Error naming the file
// (and the line where the parser knows it) for a missing, empty, truncated or malformed file, bad
// indices, NaN or Inf coordinates, or a file with no triangle geometry.
//
// Readers: VRML97 / VRML 2.0 (.wrl, .wrz, .wrl.gz; gzip is detected by its magic bytes), VRML 1.0 and
// Open Inventor (.iv) through Coin3D; OBJ, PLY, STL, OFF, glTF (.gltf/.glb) through assimp.
// Writers: VRML97 (.wrl) and PLY (.ply).
#include <filesystem>

#include "palpate/core/mesh.hpp"
#include "palpate/core/scene.hpp"

namespace palpate {

// Every drawn shape of the file as one object, its transform hierarchy baked into the positions
// (object transform = identity), its material colour in material.color, vertex colours where given.
Scene load_model(const std::filesystem::path& file);

// All shapes of the file merged into one mesh (vertex colours kept where any shape has them).
Mesh load_mesh(const std::filesystem::path& file);

// Writes by extension: .wrl (VRML97) or .ply (binary little-endian PLY with normals and colours).
void save_mesh(const Mesh& mesh, const std::filesystem::path& file);

}  // namespace palpate
