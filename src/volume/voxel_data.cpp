#include "voxel_data.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "palpate/core/error.hpp"

namespace palpate::volume {
namespace {

std::size_t size_of(VoxelType type) {
  switch (type) {
    case VoxelType::int8:
    case VoxelType::uint8:
      return 1;
    case VoxelType::int16:
    case VoxelType::uint16:
      return 2;
    case VoxelType::int32:
    case VoxelType::uint32:
    case VoxelType::float32:
      return 4;
    case VoxelType::int64:
    case VoxelType::uint64:
    case VoxelType::float64:
      return 8;
  }
  return 1;
}

template <class T>
float value_at(const unsigned char* bytes, std::size_t index, bool swap) {
  unsigned char raw[sizeof(T)];
  std::memcpy(raw, bytes + index * sizeof(T), sizeof(T));
  if (swap) std::reverse(raw, raw + sizeof(T));
  T value;
  std::memcpy(&value, raw, sizeof(T));
  return float(value);
}

// Inflates a gzip or zlib stream (zlib detects which).
std::vector<unsigned char> inflate_all(const std::vector<unsigned char>& packed, std::size_t expected,
                                       const std::filesystem::path& header) {
  std::vector<unsigned char> out(expected);
  z_stream stream{};
  if (inflateInit2(&stream, 15 + 32) != Z_OK) throw Error(header, 0, "zlib could not start");
  stream.next_in = const_cast<unsigned char*>(packed.data());
  stream.avail_in = uInt(packed.size());
  stream.next_out = out.data();
  stream.avail_out = uInt(out.size());
  const int status = inflate(&stream, Z_FINISH);
  const std::size_t produced = stream.total_out;
  inflateEnd(&stream);
  if ((status != Z_STREAM_END && status != Z_BUF_ERROR && status != Z_OK) || produced < expected) {
    throw Error(header, 0,
                "the compressed voxels are damaged or short: " + std::to_string(produced) + " of " +
                    std::to_string(expected) + " bytes");
  }
  return out;
}

}  // namespace

std::vector<float> to_floats(const void* data, std::size_t count, VoxelType type, bool swap) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::vector<float> values(count);
  for (std::size_t i = 0; i < count; ++i) {
    switch (type) {
      case VoxelType::int8:
        values[i] = value_at<std::int8_t>(bytes, i, swap);
        break;
      case VoxelType::uint8:
        values[i] = value_at<std::uint8_t>(bytes, i, swap);
        break;
      case VoxelType::int16:
        values[i] = value_at<std::int16_t>(bytes, i, swap);
        break;
      case VoxelType::uint16:
        values[i] = value_at<std::uint16_t>(bytes, i, swap);
        break;
      case VoxelType::int32:
        values[i] = value_at<std::int32_t>(bytes, i, swap);
        break;
      case VoxelType::uint32:
        values[i] = value_at<std::uint32_t>(bytes, i, swap);
        break;
      case VoxelType::int64:
        values[i] = value_at<std::int64_t>(bytes, i, swap);
        break;
      case VoxelType::uint64:
        values[i] = value_at<std::uint64_t>(bytes, i, swap);
        break;
      case VoxelType::float32:
        values[i] = value_at<float>(bytes, i, swap);
        break;
      case VoxelType::float64:
        values[i] = value_at<double>(bytes, i, swap);
        break;
    }
  }
  return values;
}

std::vector<float> read_voxels(const VoxelData& data, std::size_t count,
                               const std::filesystem::path& header) {
  std::ifstream in(data.file, std::ios::binary);
  if (!in) throw Error(header, 0, "cannot open its voxel data " + data.file.string());
  in.seekg(std::streamoff(data.offset));
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t needed = count * size_of(data.type);
  if (data.gzip) bytes = inflate_all(bytes, needed, header);
  if (bytes.size() < needed) {
    throw Error(header, 0,
                "the voxel data is short: " + std::to_string(bytes.size()) + " of " + std::to_string(needed) +
                    " bytes");
  }
  const bool swap = data.big_endian != (std::endian::native == std::endian::big) && size_of(data.type) > 1;
  return to_floats(bytes.data(), count, data.type, swap);
}

glm::dmat4 lps_to_ras(const glm::dmat3& axes_lps, const glm::dvec3& origin_lps) {
  glm::dmat4 m(1.0);
  for (int axis = 0; axis < 3; ++axis)
    m[axis] = glm::dvec4(-axes_lps[axis].x, -axes_lps[axis].y, axes_lps[axis].z, 0.0);
  m[3] = glm::dvec4(-origin_lps.x, -origin_lps.y, origin_lps.z, 1.0);
  return m;
}

}  // namespace palpate::volume
