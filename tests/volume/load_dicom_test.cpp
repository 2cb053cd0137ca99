// DICOM series written here with GDCM (tilted, anisotropic, rescaled, files named out of order) read
// back against the positions and values they were written with; folders that are not one series.
#include <gdcmAttribute.h>
#include <gdcmImageWriter.h>
#include <gdcmTrace.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <glm/geometric.hpp>

#include "palpate/core/error.hpp"
#include "palpate/volume/volume.hpp"
#include "test_paths.hpp"

namespace palpate::volume {
namespace {

struct SeriesSpec {
  std::string uid = "1.2.826.0.1.3680043.2.1125.1";
  std::string description = "head CT";
  glm::ivec3 size{6, 5, 4};
  glm::dvec3 row = glm::normalize(glm::dvec3(1.0, 0.3, 0.0));  // LPS, along i
  glm::dvec3 column =
      glm::normalize(glm::cross(glm::dvec3(0.2, 0.0, 1.0), glm::normalize(glm::dvec3(1.0, 0.3, 0.0))));
  glm::dvec2 spacing{0.8, 0.6};
  double step_mm = 1.5;
  glm::dvec3 origin{-30.0, 20.0, -10.0};
  double slope = 2.0, intercept = -1024.0;
  bool multi_frame = false;
};

glm::dvec3 normal_of(const SeriesSpec& spec) {
  return glm::normalize(glm::cross(spec.row, spec.column));
}

// Voxel (i, j, k) is stored as i + 10 j + 100 k. One file per slice, named so that their alphabetical
// order is not the slices' (k = 0, 1, 2, 3 in "im_2", "im_3", "im_0", "im_1" for 4), `skip` left out.
void write_series(const std::filesystem::path& folder, const SeriesSpec& spec, int skip = -1) {
  gdcm::Trace::SetWarning(false);  // its guesses about the tags a test leaves out
  std::filesystem::create_directories(folder);
  const int frames = spec.multi_frame ? spec.size.z : 1;
  for (int k = 0; k < spec.size.z; k += frames) {
    if (k == skip) continue;
    std::vector<std::int16_t> pixels;
    for (int f = 0; f < frames; ++f)
      for (int j = 0; j < spec.size.y; ++j)
        for (int i = 0; i < spec.size.x; ++i) pixels.push_back(std::int16_t(i + 10 * j + 100 * (k + f)));
    gdcm::ImageWriter writer;
    gdcm::Image& image = writer.GetImage();
    image.SetNumberOfDimensions(spec.multi_frame ? 3 : 2);
    image.SetDimension(0, unsigned(spec.size.x));
    image.SetDimension(1, unsigned(spec.size.y));
    if (spec.multi_frame) image.SetDimension(2, unsigned(frames));
    image.SetPixelFormat(gdcm::PixelFormat::INT16);
    image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
    image.SetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
    const glm::dvec3 position = spec.origin + normal_of(spec) * (spec.step_mm * k);
    for (unsigned axis = 0; axis < 3; ++axis)
      image.SetOrigin(axis, position[int(axis)]);  // all three on 2D too
    const double cosines[6] = {spec.row.x,    spec.row.y,    spec.row.z,
                               spec.column.x, spec.column.y, spec.column.z};
    image.SetDirectionCosines(cosines);
    image.SetSpacing(0, spec.spacing.x);
    image.SetSpacing(1, spec.spacing.y);
    image.SetSpacing(2, spec.step_mm);
    image.SetSlope(spec.slope);
    image.SetIntercept(spec.intercept);
    gdcm::DataElement data(gdcm::Tag(0x7fe0, 0x0010));
    data.SetByteValue(reinterpret_cast<const char*>(pixels.data()), std::uint32_t(pixels.size() * 2));
    image.SetDataElement(data);
    gdcm::DataSet& set = writer.GetFile().GetDataSet();
    const gdcm::MediaStorage storage(spec.multi_frame ? gdcm::MediaStorage::EnhancedCTImageStorage
                                                      : gdcm::MediaStorage::CTImageStorage);
    gdcm::DataElement sop_class(gdcm::Tag(0x0008, 0x0016));
    sop_class.SetByteValue(storage.GetString(), std::uint32_t(std::strlen(storage.GetString())));
    sop_class.SetVR(gdcm::VR::UI);
    set.Replace(sop_class);
    gdcm::Attribute<0x0020, 0x000e> series;
    series.SetValue(spec.uid.c_str());
    set.Replace(series.GetAsDataElement());
    gdcm::Attribute<0x0008, 0x0060> modality;
    modality.SetValue("CT");
    set.Replace(modality.GetAsDataElement());
    gdcm::Attribute<0x0008, 0x103e> description;
    description.SetValue(spec.description.c_str());
    set.Replace(description.GetAsDataElement());
    const int name = (k + 2) % spec.size.z;
    writer.SetFileName((folder / ("im_" + std::to_string(name))).c_str());
    ASSERT_TRUE(writer.Write()) << folder;
  }
}

void expect_the_written_series(const Volume& volume, const SeriesSpec& spec) {
  EXPECT_EQ(volume.size, spec.size);
  EXPECT_EQ(volume.frame, "DICOM Image Position and Orientation");
  for (const glm::ivec3 voxel :
       {glm::ivec3(0, 0, 0), glm::ivec3(5, 4, 3), glm::ivec3(1, 2, 3), glm::ivec3(4, 0, 1)}) {
    SCOPED_TRACE(voxel.x + 10 * voxel.y + 100 * voxel.z);
    EXPECT_FLOAT_EQ(volume.at(voxel.x, voxel.y, voxel.z),
                    float((voxel.x + 10 * voxel.y + 100 * voxel.z) * spec.slope + spec.intercept));
    const glm::dvec3 lps = spec.origin + spec.row * (spec.spacing.x * voxel.x) +
                           spec.column * (spec.spacing.y * voxel.y) +
                           normal_of(spec) * (spec.step_mm * voxel.z);
    const glm::dvec3 ras = glm::dvec3(volume.voxel_to_mm * glm::dvec4(glm::dvec3(voxel), 1.0));
    EXPECT_NEAR(ras.x, -lps.x, 1e-3);  // DICOM's text fields hold 16 characters
    EXPECT_NEAR(ras.y, -lps.y, 1e-3);
    EXPECT_NEAR(ras.z, lps.z, 1e-3);
  }
}

TEST(LoadDicom, ATiltedRescaledSeriesInShuffledFilesComesOutInRasMillimetres) {
  const auto folder = test::scratch_dir("load_dicom_series") / "series";
  const SeriesSpec spec;
  write_series(folder, spec);
  expect_the_written_series(load_volume(folder), spec);
  expect_the_written_series(load_volume(folder / "im_1"), spec);  // a file of it: its folder
}

TEST(LoadDicom, AMultiFrameFileIsAVolume) {
  const auto folder = test::scratch_dir("load_dicom_multi_frame") / "series";
  SeriesSpec spec;
  spec.multi_frame = true;
  write_series(folder, spec);
  expect_the_written_series(load_volume(folder), spec);
}

TEST(LoadDicom, FoldersThatAreNotOneWholeSeriesAreErrorsSayingWhy) {
  const auto folder = test::scratch_dir("load_dicom_errors");
  const auto fails_with = [](const std::filesystem::path& path, const std::string& what) {
    EXPECT_THAT([&] { load_volume(path); }, testing::ThrowsMessage<Error>(testing::HasSubstr(what))) << path;
  };
  SeriesSpec second;
  second.uid = "1.2.826.0.1.3680043.2.1125.2";
  second.description = "scout";
  second.size.z = 3;
  write_series(folder / "mixed", SeriesSpec{});
  write_series(folder / "mixed" / "more", second);
  fails_with(folder / "mixed",
             "2 DICOM series in one folder; put the one to read in a folder of its own:\n"
             "  1.2.826.0.1.3680043.2.1125.1  CT  \"head CT\"  4 files, e.g. im_0\n"
             "  1.2.826.0.1.3680043.2.1125.2  CT  \"scout\"  3 files, e.g. more/im_0");

  SeriesSpec five;
  five.size.z = 5;
  write_series(folder / "gap", five, 2);
  fails_with(folder / "gap",
             "slices im_3 and im_0 are 3 mm apart, the others 1.5 mm (a missing or a duplicate slice)");

  std::filesystem::create_directories(folder / "text");
  std::ofstream(folder / "text" / "notes.txt") << "not DICOM";
  fails_with(folder / "text", "a folder without DICOM files (1 files looked at)");

  SeriesSpec one;
  one.size.z = 1;
  write_series(folder / "one", one);
  fails_with(folder / "one", "a single DICOM slice is not a volume");
}

}  // namespace
}  // namespace palpate::volume
