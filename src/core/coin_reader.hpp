#pragma once
// VRML 1.0, VRML97 and Open Inventor through Coin3D (setup code: allocates, throws palpate::Error).
#include <filesystem>
#include <string>

#include "palpate/core/load.hpp"
#include "palpate/core/scene.hpp"

namespace palpate::detail {

// Reads `text` (the file's decompressed content) with SoDB::readAll, then collects the world-space
// triangles of every drawn shape with an SoCallbackAction: one object per shape instance.
Scene read_coin_model(const std::string& text, const std::filesystem::path& file, const LoadParams& options);

}  // namespace palpate::detail
