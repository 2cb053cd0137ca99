#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "core/mesh_writers.hpp"
#include "palpate/core/error.hpp"

namespace palpate::detail {
namespace {

// Appends the little-endian bytes of a 32-bit word, whatever the machine's byte order.
void put_u32(std::string& out, std::uint32_t word) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<char>((word >> shift) & 0xffu));
}
void put_f32(std::string& out, float value) {
  put_u32(out, std::bit_cast<std::uint32_t>(value));
}
void put_u8(std::string& out, float unit) {
  out.push_back(
      static_cast<char>(static_cast<std::uint8_t>(std::lround(std::clamp(unit, 0.0f, 1.0f) * 255.0f))));
}

}  // namespace

void write_ply(const Mesh& mesh, const std::filesystem::path& file) {
  const bool colored = !mesh.colors.empty();
  std::string out =
      "ply\nformat binary_little_endian 1.0\ncomment written by palpate (units: mm)\nelement vertex " +
      std::to_string(mesh.vertex_count()) +
      "\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\n" +
      (colored ? "property uchar red\nproperty uchar green\nproperty uchar blue\n" : "") + "element face " +
      std::to_string(mesh.triangle_count()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  out.reserve(out.size() + mesh.vertex_count() * (colored ? 27 : 24) + mesh.triangle_count() * 13);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    for (int axis = 0; axis < 3; ++axis) put_f32(out, mesh.positions_mm[v][axis]);
    for (int axis = 0; axis < 3; ++axis) put_f32(out, mesh.normals[v][axis]);
    if (colored) {
      for (int channel = 0; channel < 3; ++channel) put_u8(out, mesh.colors[v][channel]);
    }
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    out.push_back(3);
    for (int corner = 0; corner < 3; ++corner) put_u32(out, mesh.indices[3 * t + corner]);
  }
  std::ofstream stream(file, std::ios::binary | std::ios::trunc);
  if (!stream) throw Error(file, 0, std::string("cannot open for writing: ") + std::strerror(errno));
  stream.write(out.data(), static_cast<std::streamsize>(out.size()));
  stream.close();
  if (!stream) throw Error(file, 0, "write failed (disk full?)");
}

}  // namespace palpate::detail
