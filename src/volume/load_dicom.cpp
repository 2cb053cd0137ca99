// DICOM series through GDCM (Debian's libgdcm-dev): its Scanner groups a folder's files by series and
// its ImageReader decodes each image (every transfer syntax GDCM has a codec for, rescale applied per
// slice). The slices are ordered and spaced here, from Image Position and Orientation, so that a tilt,
// a gap or a duplicate is an error naming the files (GDCM's IPPSorter only says that it failed).
#include "load_dicom.hpp"

#include <gdcmImageHelper.h>
#include <gdcmImageReader.h>
#include <gdcmScanner.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <map>

#include "palpate/core/error.hpp"
#include "voxel_data.hpp"

namespace palpate::volume {
namespace {

const gdcm::Tag series_uid_tag(0x0020, 0x000e), description_tag(0x0008, 0x103e), modality_tag(0x0008, 0x0060);

struct Slice {
  std::string file;
  glm::ivec2 size{0};
  glm::dvec3 position{0.0}, row{0.0}, column{0.0};  // LPS: first voxel, along i, along j
  glm::dvec2 spacing{0.0};                          // along i, along j
  VoxelType type = VoxelType::uint8;
  double slope = 1.0, intercept = 0.0;
  std::vector<float> values;
  int frames = 1;  // more than one in an enhanced (multi-frame) file
  double frame_spacing = 0.0;
};

// DICOM pads its text fields to an even length with a space (a NUL for UIDs).
std::string trimmed(const char* value) {
  std::string text = value ? value : "";
  while (!text.empty() && (text.back() == ' ' || text.back() == '\0')) text.pop_back();
  return text;
}

std::string millimetres(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g mm", value);
  return text;
}

std::string name_of(const std::string& file, const std::filesystem::path& folder) {
  return std::filesystem::relative(file, folder).string();
}

VoxelType voxel_type(const gdcm::PixelFormat& format, const std::string& file) {
  switch (format.GetScalarType()) {
    case gdcm::PixelFormat::UINT8:
      return VoxelType::uint8;
    case gdcm::PixelFormat::INT8:
      return VoxelType::int8;
    case gdcm::PixelFormat::UINT12:
    case gdcm::PixelFormat::UINT16:
      return VoxelType::uint16;
    case gdcm::PixelFormat::INT12:
    case gdcm::PixelFormat::INT16:
      return VoxelType::int16;
    case gdcm::PixelFormat::UINT32:
      return VoxelType::uint32;
    case gdcm::PixelFormat::INT32:
      return VoxelType::int32;
    case gdcm::PixelFormat::FLOAT32:
      return VoxelType::float32;
    case gdcm::PixelFormat::FLOAT64:
      return VoxelType::float64;
    default:
      throw Error(file, 0,
                  std::string("unsupported DICOM pixel format ") + format.GetScalarTypeAsString() +
                      " (a scalar volume is needed: integers or floats)");
  }
}

Slice read_slice(const std::string& file) {
  gdcm::ImageReader reader;
  reader.SetFileName(file.c_str());
  if (!reader.Read()) throw Error(file, 0, "not a DICOM image GDCM can read");
  const gdcm::Image& image = reader.GetImage();
  if (image.GetPixelFormat().GetSamplesPerPixel() != 1)
    throw Error(file, 0, "a colour image (a scalar CT or MR volume is needed)");
  Slice slice;
  slice.file = file;
  slice.size = {int(image.GetDimension(0)), int(image.GetDimension(1))};
  slice.frames = image.GetNumberOfDimensions() > 2 ? int(image.GetDimension(2)) : 1;
  slice.position = {image.GetOrigin(0), image.GetOrigin(1), image.GetOrigin(2)};
  const double* cosines = image.GetDirectionCosines();
  slice.row = {cosines[0], cosines[1], cosines[2]};
  slice.column = {cosines[3], cosines[4], cosines[5]};
  slice.spacing = {image.GetSpacing(0), image.GetSpacing(1)};
  slice.frame_spacing = image.GetSpacing(2);
  slice.type = voxel_type(image.GetPixelFormat(), file);
  slice.slope = image.GetSlope();
  slice.intercept = image.GetIntercept();
  std::vector<char> bytes(image.GetBufferLength());
  const std::size_t count = std::size_t(slice.size.x) * std::size_t(slice.size.y) * std::size_t(slice.frames);
  const std::size_t bits = image.GetPixelFormat().GetBitsAllocated();
  if (!image.GetBuffer(bytes.data()) || bytes.size() < count * bits / 8)
    throw Error(file, 0,
                "its pixel data could not be decoded (transfer syntax " +
                    std::string(gdcm::TransferSyntax::GetTSString(image.GetTransferSyntax())) + ")");
  slice.values = to_floats(bytes.data(), count, slice.type, false);  // GDCM gives this machine's order
  for (float& value : slice.values) value = float(value * slice.slope + slice.intercept);
  return slice;
}

std::map<std::string, std::vector<std::string>> series_in(const std::filesystem::path& folder,
                                                          gdcm::Scanner& scanner) {
  std::vector<std::string> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder, error))
    if (entry.is_regular_file(error)) files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  scanner.AddTag(series_uid_tag);
  scanner.AddTag(description_tag);
  scanner.AddTag(modality_tag);
  if (!files.empty() && !scanner.Scan(files)) throw Error(folder, 0, "its files could not be scanned");
  std::map<std::string, std::vector<std::string>> series;
  for (const std::string& file : files) {
    if (!scanner.IsKey(file.c_str())) continue;  // not DICOM
    const std::string uid = trimmed(scanner.GetValue(file.c_str(), series_uid_tag));
    series[uid.empty() ? "(no series UID)" : uid].push_back(file);
  }
  if (series.empty())
    throw Error(folder, 0,
                "a folder without DICOM files (" + std::to_string(files.size()) + " files looked at)");
  if (series.size() > 1) {
    std::string list;
    for (const auto& [uid, members] : series) {
      const std::string modality = trimmed(scanner.GetValue(members.front().c_str(), modality_tag));
      list += "\n  " + uid + "  " + (modality.empty() ? "?" : modality) + "  \"" +
              trimmed(scanner.GetValue(members.front().c_str(), description_tag)) + "\"  " +
              std::to_string(members.size()) + " files, e.g. " + name_of(members.front(), folder);
    }
    throw Error(folder, 0,
                std::to_string(series.size()) +
                    " DICOM series in one folder; put the one to read in a folder of its own:" + list);
  }
  return series;
}

Volume volume_of(Slice&& first, int slices, const glm::dvec3& step_lps, const std::filesystem::path& source) {
  Volume volume;
  volume.source = source;
  volume.size = {first.size.x, first.size.y, slices};
  volume.voxel_to_mm = lps_to_ras(
      glm::dmat3(first.row * first.spacing.x, first.column * first.spacing.y, step_lps), first.position);
  volume.frame = "DICOM Image Position and Orientation";
  volume.values = std::move(first.values);
  return volume;
}

}  // namespace

Volume load_dicom(const std::filesystem::path& folder) {
  gdcm::Trace::SetWarning(false);  // GDCM's messages would go to stderr; ours name the file
  gdcm::Trace::SetError(false);
  gdcm::ImageHelper::SetForceRescaleInterceptSlope(true);  // MR series carry rescales too
  gdcm::Scanner scanner;
  const auto series = series_in(folder, scanner);
  const std::vector<std::string>& files = series.begin()->second;

  if (files.size() == 1) {  // an enhanced (multi-frame) file holds the whole volume
    Slice only = read_slice(files.front());
    if (only.frames < 2) throw Error(files.front(), 0, "a single DICOM slice is not a volume");
    const glm::dvec3 normal = glm::normalize(glm::cross(only.row, only.column));
    const int frames = only.frames;
    const double spacing = only.frame_spacing;
    return volume_of(std::move(only), frames, normal * spacing, folder);
  }

  std::vector<Slice> slices;
  for (const std::string& file : files) slices.push_back(read_slice(file));
  const Slice& reference = slices.front();
  const glm::dvec3 normal = glm::normalize(glm::cross(reference.row, reference.column));
  for (const Slice& slice : slices) {
    if (slice.size != reference.size || slice.frames != 1) {
      throw Error(slice.file, 0,
                  "its image is " + std::to_string(slice.size.x) + " x " + std::to_string(slice.size.y) +
                      " (x " + std::to_string(slice.frames) + "), the series' first is " +
                      std::to_string(reference.size.x) + " x " + std::to_string(reference.size.y));
    }
    if (glm::distance(slice.row, reference.row) > 1e-4 ||
        glm::distance(slice.column, reference.column) > 1e-4 ||
        glm::distance(slice.spacing, reference.spacing) > 1e-4) {
      throw Error(slice.file, 0,
                  "its orientation or pixel spacing differs from " + name_of(reference.file, folder) +
                      "'s (a tilted or reformatted series)");
    }
  }
  std::sort(slices.begin(), slices.end(), [&](const Slice& a, const Slice& b) {
    return glm::dot(a.position, normal) < glm::dot(b.position, normal);
  });
  const glm::dvec3 step = (slices.back().position - slices.front().position) / double(slices.size() - 1);
  // Each gap against the typical one (the median), so that the message names the odd pair.
  std::vector<double> gaps;
  for (std::size_t s = 1; s < slices.size(); ++s)
    gaps.push_back(glm::length(slices[s].position - slices[s - 1].position));
  std::vector<double> sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  const double typical = sorted[sorted.size() / 2];
  for (std::size_t s = 1; s < slices.size(); ++s) {
    const double gap = gaps[s - 1];
    if (gap < 1e-3 * std::max(typical, 1e-6) || std::abs(gap - typical) > 0.01 * typical + 1e-4) {
      throw Error(folder, 0,
                  "slices " + name_of(slices[s - 1].file, folder) + " and " +
                      name_of(slices[s].file, folder) + " are " + millimetres(gap) + " apart, the others " +
                      millimetres(typical) + " (a missing or a duplicate slice)");
    }
  }
  const int count = int(slices.size());
  std::vector<float> values;
  values.reserve(slices.front().values.size() * slices.size());
  for (const Slice& slice : slices) values.insert(values.end(), slice.values.begin(), slice.values.end());
  slices.front().values = std::move(values);
  return volume_of(std::move(slices.front()), count, step, folder);
}

}  // namespace palpate::volume
