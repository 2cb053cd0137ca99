#pragma once
// Two pictures of the same size compared pixel by pixel (the sum of the RGB differences, 0..765):
// where they differ by more than 6, near a point (within `reach_px`) or away from it; the mean and the
// worst difference. The toolkit tests' measure of "dents like the CPU reference and nowhere else".
#include <cstdint>
#include <glm/vec2.hpp>
#include <span>

namespace palpate::test {

struct PictureComparison {
  int changed_near = 0, changed_far = 0;
  double mean = 0.0;
  int worst = 0;
};

// `channels` bytes a pixel (3: RGB, 4: RGBA), rows of `width` pixels.
PictureComparison compare_pictures(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b,
                                   int width, int height, int channels, glm::vec2 centre_px, float reach_px);

}  // namespace palpate::test
