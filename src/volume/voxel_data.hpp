#pragma once
// The voxel bytes of volume formats with a text header (NRRD, MetaImage): where they are, how they are
// compressed and stored, converted to floats.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "palpate/volume/volume.hpp"

namespace palpate::volume {

enum class VoxelType { int8, uint8, int16, uint16, int32, uint32, int64, uint64, float32, float64 };

struct VoxelData {
  std::filesystem::path file;  // the file holding the voxels
  std::size_t offset = 0;      // bytes before them
  bool gzip = false;           // gzip or zlib stream (either is inflated)
  bool big_endian = false;
  VoxelType type = VoxelType::uint8;
};

// `count` values of `type` stored at `bytes` as floats, each byte-swapped first when `swap`.
std::vector<float> to_floats(const void* bytes, std::size_t count, VoxelType type, bool swap);

// `count` voxels as floats. Throws palpate::Error naming `header` when the file is missing or short.
std::vector<float> read_voxels(const VoxelData& data, std::size_t count, const std::filesystem::path& header);

// The matrix from voxel indices to RAS millimetres, from the format's LPS axes (one column per axis,
// its direction times its spacing) and origin: RAS negates x and y.
glm::dmat4 lps_to_ras(const glm::dmat3& axes_lps, const glm::dvec3& origin_lps);

}  // namespace palpate::volume
