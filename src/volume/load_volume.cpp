#include <nifti1_io.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <memory>

#include "load_dicom.hpp"
#include "palpate/core/error.hpp"
#include "palpate/volume/volume.hpp"
#include "text_header.hpp"
#include "voxel_data.hpp"

namespace palpate::volume {
namespace {

bool has_extension(const std::filesystem::path& file, std::initializer_list<const char*> extensions) {
  std::string name = file.filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  return std::any_of(extensions.begin(), extensions.end(), [&](const char* extension) {
    return name.size() > std::string_view(extension).size() && name.ends_with(extension);
  });
}

// DICOM Part 10 files start with a 128-byte preamble and "DICM", whatever their names (often none).
bool is_dicom_file(const std::filesystem::path& file) {
  char magic[132] = {};
  std::ifstream(file, std::ios::binary).read(magic, sizeof magic);
  return std::string_view(magic + 128, 4) == "DICM";
}

void check_size(const Volume& volume) {
  if (volume.size.x < 2 || volume.size.y < 2 || volume.size.z < 2) {
    throw Error(volume.source, 0,
                "not a volume: " + std::to_string(volume.size.x) + " x " + std::to_string(volume.size.y) +
                    " x " + std::to_string(volume.size.z) +
                    " voxels (an isosurface needs at least 2 along each axis)");
  }
}

Volume load_nifti(const std::filesystem::path& file) {
  nifti_set_debug_level(0);  // its messages would go to stderr; ours name the file
  const std::unique_ptr<nifti_image, decltype(&nifti_image_free)> image(nifti_image_read(file.c_str(), 1),
                                                                        &nifti_image_free);
  if (!image || !image->data)
    throw Error(file, 0, "not a readable NIfTI-1 volume (niftiio could not read it)");
  Volume volume;
  volume.source = file;
  volume.size = {int(image->nx), int(image->ny), int(image->nz)};
  check_size(volume);
  const std::size_t count = std::size_t(image->nx) * std::size_t(image->ny) * std::size_t(image->nz);
  // NIfTI: a slope of 0 means "no scaling".
  const bool scaled =
      image->scl_slope != 0.0f && std::isfinite(image->scl_slope) && std::isfinite(image->scl_inter);
  const float slope = scaled ? image->scl_slope : 1.0f, intercept = scaled ? image->scl_inter : 0.0f;
  static const std::map<int, VoxelType> types = {
      {DT_UINT8, VoxelType::uint8},    {DT_INT8, VoxelType::int8},     {DT_INT16, VoxelType::int16},
      {DT_UINT16, VoxelType::uint16},  {DT_INT32, VoxelType::int32},   {DT_UINT32, VoxelType::uint32},
      {DT_INT64, VoxelType::int64},    {DT_UINT64, VoxelType::uint64}, {DT_FLOAT32, VoxelType::float32},
      {DT_FLOAT64, VoxelType::float64}};
  const auto type = types.find(image->datatype);
  if (type == types.end()) {
    throw Error(file, 0,
                std::string("unsupported data type ") + nifti_datatype_string(image->datatype) +
                    " (a scalar volume is needed: integers or floats)");
  }
  // niftiio has already swapped the bytes to this machine's order. Only the first volume of a series.
  volume.values = to_floats(image->data, count, type->second, false);
  for (float& value : volume.values) value = value * slope + intercept;
  const auto to_glm = [](const mat44& m) {
    glm::dmat4 out(1.0);
    for (int row = 0; row < 4; ++row)
      for (int column = 0; column < 4; ++column) out[column][row] = m.m[row][column];
    return out;
  };
  if (image->sform_code > 0) {
    volume.voxel_to_mm = to_glm(image->sto_xyz);
    volume.frame = "NIfTI sform (code " + std::to_string(image->sform_code) + ")";
  } else if (image->qform_code > 0) {
    volume.voxel_to_mm = to_glm(image->qto_xyz);
    volume.frame = "NIfTI qform (code " + std::to_string(image->qform_code) + ")";
  } else {
    volume.voxel_to_mm = glm::dmat4(1.0);
    volume.voxel_to_mm[0][0] = image->dx > 0 ? image->dx : 1.0;
    volume.voxel_to_mm[1][1] = image->dy > 0 ? image->dy : 1.0;
    volume.voxel_to_mm[2][2] = image->dz > 0 ? image->dz : 1.0;
    volume.frame = "NIfTI voxel sizes (no sform or qform)";
  }
  return volume;
}

}  // namespace

IntensityRange intensity_range(const Volume& volume) noexcept {
  if (volume.values.empty()) return {};
  const auto [low, high] = std::minmax_element(volume.values.begin(), volume.values.end());
  return {*low, *high};
}

Volume load_volume(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::exists(file, error)) throw Error(file, 0, "no such file or folder");
  if (std::filesystem::is_directory(file, error)) return load_dicom(file);
  if (has_extension(file, {".nii", ".nii.gz"})) return load_nifti(file);
  if (has_extension(file, {".nrrd", ".nhdr"})) return load_nrrd(file);
  if (has_extension(file, {".mha", ".mhd"})) return load_metaimage(file);
  if (has_extension(file, {".dcm"}) || is_dicom_file(file))
    return load_dicom(file.parent_path());  // its series
  throw Error(
      file, 0,
      "not a volume format palpate reads (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd, or a DICOM series' "
      "folder)");
}

float otsu_threshold(const Volume& volume, float below) {
  IntensityRange range = intensity_range(volume);
  range.max = std::min(range.max, below);
  if (!(range.max > range.min)) throw Error(volume.source, 0, "a constant volume has no threshold");
  constexpr int bins = 256;
  std::vector<double> histogram(bins, 0.0);
  const double scale = (bins - 1) / double(range.max - range.min);
  double total = 0.0;
  for (const float value : volume.values) {
    if (value > range.max) continue;
    histogram[std::size_t((value - range.min) * scale)] += 1.0;
    total += 1.0;
  }
  double sum_all = 0.0;
  for (int b = 0; b < bins; ++b) sum_all += b * histogram[std::size_t(b)];
  double weight_below = 0.0, sum_below = 0.0, best_variance = -1.0;
  int best = 0;
  for (int b = 0; b < bins - 1; ++b) {
    weight_below += histogram[std::size_t(b)];
    sum_below += b * histogram[std::size_t(b)];
    const double weight_above = total - weight_below;
    if (weight_below == 0.0 || weight_above == 0.0) continue;
    const double mean_below = sum_below / weight_below, mean_above = (sum_all - sum_below) / weight_above;
    const double variance =
        weight_below * weight_above * (mean_below - mean_above) * (mean_below - mean_above);
    if (variance > best_variance) best_variance = variance, best = b;
  }
  return range.min + float((best + 0.5) / scale);  // between bin `best` and the next
}

float air_threshold(const Volume& volume) {
  return otsu_threshold(volume, otsu_threshold(volume));
}

}  // namespace palpate::volume
