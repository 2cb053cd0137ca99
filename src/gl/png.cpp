#include "palpate/gl/png.hpp"

#include <stb/stb_image_write.h>  // implemented in Debian's libstb

#include <string>

#include "palpate/core/error.hpp"

namespace palpate::gl {

void save_png(const std::filesystem::path& file, int width, int height, std::span<const std::uint8_t> rgba) {
  if (width <= 0 || height <= 0 ||
      rgba.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
    throw Error(file, 0,
                "save_png: " + std::to_string(rgba.size()) + " bytes do not make a " + std::to_string(width) +
                    "x" + std::to_string(height) + " RGBA image");
  }
  // A negative stride walks the rows from the last in memory (the top row) down to the first.
  const std::uint8_t* top_row = rgba.data() + static_cast<std::size_t>(height - 1) * width * 4;
  if (!stbi_write_png(file.c_str(), width, height, 4, top_row, -width * 4)) {
    throw Error(file, 0, "save_png: cannot write the file");
  }
}

}  // namespace palpate::gl
