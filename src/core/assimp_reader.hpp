#pragma once
// OBJ, PLY, STL, OFF, glTF and X3D XML through assimp (setup code: allocates, throws palpate::Error).
#include <filesystem>
#include <string>

#include "palpate/core/load.hpp"
#include "palpate/core/scene.hpp"

namespace palpate::detail {

struct AssimpInput {
  std::filesystem::path file;           // named in errors; read from disk when `memory` is null
  const std::string* memory = nullptr;  // the decompressed content of a gzipped file
  std::string format_hint;              // extension without the dot, for `memory` ("x3d")
  bool weld_positions = false;          // OBJ and STL: one vertex per distinct position (see load.hpp)
};

Scene read_assimp_model(const AssimpInput& input, const LoadParams& options);

}  // namespace palpate::detail
