#include "picture_comparison.hpp"

#include <algorithm>
#include <cstdlib>
#include <glm/geometric.hpp>

namespace palpate::test {

PictureComparison compare_pictures(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b,
                                   int width, int height, int channels, glm::vec2 centre_px, float reach_px) {
  PictureComparison result;
  double sum = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t at = std::size_t(channels) * (std::size_t(y) * std::size_t(width) + std::size_t(x));
      int difference = 0;
      for (std::size_t c = 0; c < 3; ++c) difference += std::abs(int(a[at + c]) - int(b[at + c]));
      sum += difference;
      result.worst = std::max(result.worst, difference);
      if (difference <= 6) continue;
      (glm::distance(glm::vec2(x, y), centre_px) <= reach_px ? result.changed_near : result.changed_far) += 1;
    }
  }
  result.mean = sum / double(width * height);
  return result;
}

}  // namespace palpate::test
