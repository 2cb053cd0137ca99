// Reading volumes: NIfTI files written here with niftiio (scale slope, sform and qform, data types,
// compressed or not), malformed files, and the real head and brain volumes in ../shared/data.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nifti1_io.h>
#include <zlib.h>

#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "palpate/core/error.hpp"
#include "palpate/core/mesh_topology.hpp"
#include "palpate/volume/isosurface.hpp"
#include "palpate/volume/volume.hpp"
#include "test_paths.hpp"

namespace palpate::volume {
namespace {

struct NiftiSpec {
  int datatype = DT_INT16;
  float slope = 0.0f, intercept = 0.0f;
  int sform_code = 0, qform_code = 0;
  glm::dmat4 sform{1.0};
  int nz = 4;
};

// A 5 x 3 x nz volume whose raw voxel value is i + 10 j + 100 k (stored as `datatype`).
std::filesystem::path write_nifti(const std::filesystem::path& file, const NiftiSpec& spec) {
  const int dims[8] = {3, 5, 3, spec.nz, 1, 1, 1, 1};
  nifti_image* image = nifti_make_new_nim(dims, spec.datatype, 1);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) {
        const std::size_t at = std::size_t(i + 5 * (j + 3 * k));
        const int raw = i + 10 * j + 100 * k;
        if (spec.datatype == DT_INT16) static_cast<std::int16_t*>(image->data)[at] = std::int16_t(raw);
        if (spec.datatype == DT_FLOAT32) static_cast<float*>(image->data)[at] = float(raw);
        if (spec.datatype == DT_UINT8) static_cast<std::uint8_t*>(image->data)[at] = std::uint8_t(raw % 256);
      }
  image->scl_slope = spec.slope;
  image->scl_inter = spec.intercept;
  image->sform_code = spec.sform_code;
  image->qform_code = spec.qform_code;
  image->dx = image->pixdim[1] = 2.0f;
  image->dy = image->pixdim[2] = 3.0f;
  image->dz = image->pixdim[3] = 4.0f;
  for (int row = 0; row < 4; ++row)
    for (int column = 0; column < 4; ++column) image->sto_xyz.m[row][column] = float(spec.sform[column][row]);
  if (spec.qform_code > 0) {  // a pure scaling by the voxel sizes, shifted
    image->quatern_b = image->quatern_c = image->quatern_d = 0.0f;
    image->qoffset_x = 7.0f, image->qoffset_y = 8.0f, image->qoffset_z = 9.0f;
    image->qfac = 1.0f;
  }
  nifti_set_filenames(image, file.c_str(), 0, 1);
  nifti_image_write(image);
  nifti_image_free(image);
  return file;
}

TEST(LoadVolume, NiftiAppliesTheScaleSlopeAndTakesTheSform) {
  const auto folder = test::scratch_dir("load_volume_nifti");
  glm::dmat4 sform = glm::translate(glm::dmat4(1.0), glm::dvec3(-90, 126, -72));
  sform = glm::scale(sform, glm::dvec3(-2.0, 2.0, 2.0));  // LAS, as SPM writes
  const Volume volume = load_volume(write_nifti(
      folder / "scaled.nii.gz",
      {.datatype = DT_INT16, .slope = 0.5f, .intercept = -3.0f, .sform_code = 4, .sform = sform}));
  EXPECT_EQ(volume.size, glm::ivec3(5, 3, 4));
  EXPECT_FLOAT_EQ(volume.at(4, 2, 3), (4 + 20 + 300) * 0.5f - 3.0f);
  EXPECT_FLOAT_EQ(volume.at(0, 0, 0), -3.0f);
  const glm::dvec3 corner = glm::dvec3(volume.voxel_to_mm * glm::dvec4(4, 2, 3, 1));
  EXPECT_NEAR(corner.x, -90.0 - 8.0, 1e-4);
  EXPECT_NEAR(corner.y, 126.0 + 4.0, 1e-4);
  EXPECT_NEAR(corner.z, -72.0 + 6.0, 1e-4);
  EXPECT_EQ(volume.frame, "NIfTI sform (code 4)");
  const IntensityRange range = intensity_range(volume);
  EXPECT_FLOAT_EQ(range.min, -3.0f);
  EXPECT_FLOAT_EQ(range.max, 324 * 0.5f - 3.0f);
}

TEST(LoadVolume, NiftiWithoutSformTakesTheQformThenTheVoxelSizes) {
  const auto folder = test::scratch_dir("load_volume_qform");
  const Volume with_qform =
      load_volume(write_nifti(folder / "q.nii", {.datatype = DT_FLOAT32, .qform_code = 1}));
  EXPECT_EQ(with_qform.frame, "NIfTI qform (code 1)");
  const glm::dvec3 p = glm::dvec3(with_qform.voxel_to_mm * glm::dvec4(1, 1, 1, 1));
  EXPECT_NEAR(p.x, 7.0 + 2.0, 1e-4);
  EXPECT_NEAR(p.y, 8.0 + 3.0, 1e-4);
  EXPECT_NEAR(p.z, 9.0 + 4.0, 1e-4);
  EXPECT_FLOAT_EQ(with_qform.at(1, 2, 3), 321.0f);  // slope 0: unscaled

  const Volume bare = load_volume(write_nifti(folder / "bare.nii", {.datatype = DT_UINT8}));
  EXPECT_EQ(bare.frame, "NIfTI voxel sizes (no sform or qform)");
  EXPECT_EQ(glm::dvec3(bare.voxel_to_mm * glm::dvec4(1, 1, 1, 1)), glm::dvec3(2, 3, 4));
}

// The voxels i + 10 j + 100 k of a 5 x 3 x 4 grid as little-endian int16, compressed as gzip
// (`gzip_header`) or as a zlib stream.
std::string packed_voxels(bool compress, bool gzip_header) {
  std::string raw;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) {
        const std::int16_t v = std::int16_t(i + 10 * j + 100 * k);
        raw.push_back(char(v & 0xff));
        raw.push_back(char((v >> 8) & 0xff));
      }
  if (!compress) return raw;
  z_stream stream{};
  deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, gzip_header ? 31 : 15, 8, Z_DEFAULT_STRATEGY);
  std::string out(raw.size() + 128, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(raw.data());
  stream.avail_in = uInt(raw.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = uInt(out.size());
  deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

// The same grid, its axes turned (i along -y, j along +x, in LPS) and spaced 2, 3, 4 mm, its first voxel
// at LPS (7, 8, 9): as NRRD (gzip, attached), NRRD (raw, detached) and MetaImage (zlib, LOCAL). In RAS:
// x and y negated.
TEST(LoadVolume, NrrdAndMetaImagePlaceTurnedVoxelsInRasMillimetres) {
  const auto folder = test::scratch_dir("load_volume_text_headers");
  std::ofstream(folder / "turned.nrrd", std::ios::binary)
      << "NRRD0004\n# palpate test\ntype: short\ndimension: 3\nspace: left-posterior-superior\nsizes: 5 3 4\n"
         "space directions: (0,-2,0) (3,0,0) (0,0,4)\nspace origin: (7,8,9)\nencoding: gzip\nendian: "
         "little\n\n"
      << packed_voxels(true, true);
  std::ofstream(folder / "turned.raw", std::ios::binary) << packed_voxels(false, false);
  std::ofstream(folder / "detached.nhdr", std::ios::binary)
      << "NRRD0004\ntype: int16\ndimension: 3\nspace: LPS\nsizes: 5 3 4\n"
         "space directions: (0,-2,0) (3,0,0) (0,0,4)\nspace origin: (7,8,9)\nencoding: raw\nendian: little\n"
         "data file: turned.raw\n";
  std::ofstream(folder / "turned.mha", std::ios::binary)
      << "ObjectType = Image\nNDims = 3\nDimSize = 5 3 4\nElementSpacing = 2 3 4\nOffset = 7 8 9\n"
         "TransformMatrix = 0 -1 0 1 0 0 0 0 1\nElementType = MET_SHORT\nElementByteOrderMSB = False\n"
         "CompressedData = True\nElementDataFile = LOCAL\n"
      << packed_voxels(true, false);
  for (const char* name : {"turned.nrrd", "detached.nhdr", "turned.mha"}) {
    SCOPED_TRACE(name);
    const Volume volume = load_volume(folder / name);
    EXPECT_EQ(volume.size, glm::ivec3(5, 3, 4));
    EXPECT_FLOAT_EQ(volume.at(4, 2, 3), 324.0f);
    EXPECT_FLOAT_EQ(volume.at(1, 0, 2), 201.0f);
    // Voxel (1, 2, 3): LPS (7, 8, 9) + 1 (0, -2, 0) + 2 (3, 0, 0) + 3 (0, 0, 4) = (13, 6, 21).
    const glm::dvec3 p = glm::dvec3(volume.voxel_to_mm * glm::dvec4(1, 2, 3, 1));
    EXPECT_NEAR(p.x, -13.0, 1e-9);
    EXPECT_NEAR(p.y, -6.0, 1e-9);
    EXPECT_NEAR(p.z, 21.0, 1e-9);
  }
  std::ofstream(folder / "short.nrrd", std::ios::binary)
      << "NRRD0004\ntype: short\ndimension: 3\nsizes: 5 3 4\nencoding: raw\nendian: little\n\n"
      << packed_voxels(false, false).substr(0, 50);
  EXPECT_THAT([&] { load_volume(folder / "short.nrrd"); },
              testing::ThrowsMessage<Error>(testing::HasSubstr("the voxel data is short: 50 of 120 bytes")));
}

TEST(LoadVolume, BadVolumesAreErrorsNamingTheFileAndWhatIsWrong) {
  const auto folder = test::scratch_dir("load_volume_errors");
  const auto fails_with = [](const std::filesystem::path& file, const std::string& what) {
    EXPECT_THAT([&] { load_volume(file); }, testing::ThrowsMessage<Error>(testing::AllOf(
                                                testing::HasSubstr(file.string()), testing::HasSubstr(what))))
        << file;
  };
  fails_with(folder / "absent.nii.gz", "no such file");
  std::ofstream(folder / "text.nii")
      << "this is not a NIfTI file, only some text that is long enough to be read\n";
  fails_with(folder / "text.nii", "not a readable NIfTI-1 volume");
  fails_with(write_nifti(folder / "flat.nii", {.nz = 1}), "not a volume: 5 x 3 x 1 voxels");
  fails_with(write_nifti(folder / "complex.nii", {.datatype = DT_COMPLEX64}),
             "unsupported data type COMPLEX64");
  std::ofstream(folder / "scan.mnc") << "x";
  fails_with(folder / "scan.mnc", "not a volume format palpate reads");
  fails_with(folder, "a folder without DICOM files");
  std::ofstream(folder / "broken.nrrd") << "NRRD0004\ntype: banana\n";
  fails_with(folder / "broken.nrrd", "NRRD");
}

TEST(Otsu, SplitsTwoPopulationsBetweenThem) {
  Volume volume;
  volume.size = {10, 10, 10};
  volume.values.assign(1000, 10.0f);
  for (std::size_t i = 0; i < 400; ++i) volume.values[i] = 200.0f;
  const float threshold = otsu_threshold(volume);
  EXPECT_GT(threshold, 10.0f);
  EXPECT_LT(threshold, 200.0f);
}

// A head's histogram: much air, dark tissue (skin, CSF, skull), bright tissue. Otsu's threshold falls
// between dark and bright; the air threshold between air and dark, where the skin's edge is.
TEST(Otsu, AirThresholdSplitsAirFromTheDarkestTissue) {
  Volume volume;
  volume.size = {10, 10, 10};
  volume.values.assign(1000, 2.0f);                                   // air
  for (std::size_t i = 0; i < 250; ++i) volume.values[i] = 30.0f;     // dark tissue
  for (std::size_t i = 250; i < 500; ++i) volume.values[i] = 200.0f;  // bright tissue
  const float tissue = otsu_threshold(volume), air = air_threshold(volume);
  EXPECT_GT(tissue, 30.0f);
  EXPECT_LT(tissue, 200.0f);
  EXPECT_GT(air, 2.0f);
  EXPECT_LT(air, 30.0f);
}

// The real volumes: heads closed against their border, the skull-stripped template's brain; each
// surface closed and manifold, within the volume's extent (measured: spm12 heads 180 x 209 x 174 and
// 168 x 209 x 172 mm, the 2009a brain 144 x 180 x 154 mm).
TEST(RealVolumes, HeadsAndBrainAreClosedManifoldsWithinTheirScans) {
  PALPATE_REQUIRE_SHARED_DATA(data);
  for (const char* name : {"volumes/spm12_single_subj_T1.nii", "volumes/spm12_avg152T1.nii",
                           "volumes/mni_icbm152_t1_tal_nlin_sym_09a_converted.nii.gz"}) {
    SCOPED_TRACE(name);
    const Volume volume = load_volume(data / name);
    const Isosurface surface = extract_isosurface(
        volume, {.iso = otsu_threshold(volume), .smooth_voxels = 1.0f, .largest = true, .closed = true});
    const MeshTopology topology = analyze_topology(surface.mesh);
    EXPECT_TRUE(topology.closed());
    EXPECT_TRUE(topology.manifold());
    EXPECT_TRUE(topology.oriented());
    EXPECT_EQ(topology.components, 1u);
    // Within the scan's extent (its voxel centres' box, grown by the padding voxel).
    glm::dvec3 low(1e9), high(-1e9);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 voxel((corner & 1) ? volume.size.x : -1, (corner & 2) ? volume.size.y : -1,
                             (corner & 4) ? volume.size.z : -1);
      const glm::dvec3 p = glm::dvec3(volume.voxel_to_mm * glm::dvec4(voxel, 1.0));
      low = glm::min(low, p), high = glm::max(high, p);
    }
    const Bounds box = bounds(surface.mesh);
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(glm::dvec3(box.min_mm), low)));
    EXPECT_TRUE(glm::all(glm::lessThanEqual(glm::dvec3(box.max_mm), high)));
    EXPECT_GT(box.size_mm().y, 140.0f) << "a head or brain is longer than 14 cm front to back";
  }
}

}  // namespace
}  // namespace palpate::volume
