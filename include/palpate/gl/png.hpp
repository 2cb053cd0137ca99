#pragma once
// PNG capture of rendered frames.
#include <cstdint>
#include <filesystem>
#include <span>

namespace palpate::gl {

// Writes `width` x `height` 8-bit RGBA pixels, bottom row first (as glReadPixels and
// Framebuffer::read_rgba8 give them), to `file` as a PNG. Throws palpate::Error naming the file when
// the size does not match or the file cannot be written.
void save_png(const std::filesystem::path& file, int width, int height, std::span<const std::uint8_t> rgba);

}  // namespace palpate::gl
