#include "image.hpp"

#include <algorithm>

#include "palpate/core/error.hpp"

namespace palpate::cli {

Image downsample(const Image& image, int factor) {
  Image out{image.width / factor, image.height / factor, {}};
  out.rgba.resize(std::size_t(out.width) * std::size_t(out.height) * 4);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      for (int c = 0; c < 4; ++c) {
        unsigned sum = 0;
        for (int dy = 0; dy < factor; ++dy) {
          for (int dx = 0; dx < factor; ++dx) {
            sum += image.rgba[(std::size_t(y * factor + dy) * std::size_t(image.width) +
                               std::size_t(x * factor + dx)) *
                                  4 +
                              std::size_t(c)];
          }
        }
        out.rgba[(std::size_t(y) * std::size_t(out.width) + std::size_t(x)) * 4 + std::size_t(c)] =
            std::uint8_t(sum / unsigned(factor * factor));
      }
    }
  }
  return out;
}

Image tile(const std::vector<Image>& images, int columns, int gap) {
  if (images.empty()) throw Error("contact sheet: no images");
  const int w = images.front().width, h = images.front().height;
  const int rows = (int(images.size()) + columns - 1) / columns;
  Image sheet{columns * (w + gap) + gap, rows * (h + gap) + gap, {}};
  sheet.rgba.assign(std::size_t(sheet.width) * std::size_t(sheet.height) * 4, 24);
  for (std::size_t i = 0; i < sheet.rgba.size(); i += 4) sheet.rgba[i + 3] = 255;
  for (std::size_t i = 0; i < images.size(); ++i) {
    const Image& image = images[i];
    if (image.width != w || image.height != h) throw Error("contact sheet: images differ in size");
    const int column = int(i) % columns, row = int(i) / columns;
    const int x0 = gap + column * (w + gap);
    const int y0 = sheet.height - (gap + row * (h + gap)) - h;  // bottom row first: the first row on top
    for (int y = 0; y < h; ++y) {
      std::copy_n(&image.rgba[std::size_t(y) * std::size_t(w) * 4], std::size_t(w) * 4,
                  &sheet.rgba[(std::size_t(y0 + y) * std::size_t(sheet.width) + std::size_t(x0)) * 4]);
    }
  }
  return sheet;
}

}  // namespace palpate::cli
