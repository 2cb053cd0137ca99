#pragma once
// RGBA8 images in memory, bottom row first (as OpenGL reads them), for frames and contact sheets.
#include <cstdint>
#include <vector>

namespace palpate::cli {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // bottom row first
};

// Averages each `factor` x `factor` block (the size is cut down to a multiple of `factor`).
Image downsample(const Image& image, int factor);

// Tiles equally sized images into `columns` columns, the first image at the top left, with a
// `gap`-pixel dark border around each.
Image tile(const std::vector<Image>& images, int columns, int gap = 4);

}  // namespace palpate::cli
