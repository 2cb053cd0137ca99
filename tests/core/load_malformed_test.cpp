// Broken variants of real files, made in the test: every one is a palpate::Error that names the
// file (and the line where the parser knows it), never a crash, a hang or an empty mesh.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/core/load.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::filesystem::path write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
  return file;
}

// Replaces, at the first occurrence of `marker`, the token that follows it (up to the next
// whitespace) with `replacement`, failing the test when the marker is absent.
std::string replace_token_after(const std::string& text, const std::string& marker,
                                const std::string& replacement) {
  const std::size_t at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  if (at == std::string::npos) return text;
  std::size_t begin = at + marker.size();
  while (begin < text.size() && std::isspace(static_cast<unsigned char>(text[begin]))) ++begin;
  std::size_t end = begin;
  while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
  return text.substr(0, begin) + replacement + text.substr(end);
}

// Replaces the rest of the line after the first occurrence of `marker`.
std::string replace_line_after(const std::string& text, const std::string& marker,
                               const std::string& replacement) {
  const std::size_t at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  if (at == std::string::npos) return text;
  const std::size_t end = text.find('\n', at + marker.size());
  return text.substr(0, at + marker.size()) + replacement + text.substr(end);
}

// The load fails with a palpate::Error for `file`, whose message contains `words`; returns it.
Error expect_load_error(const std::filesystem::path& file, const std::string& words, int line = -1) {
  try {
    const Scene scene = load_model(file);
    ADD_FAILURE() << file << " loaded (" << scene.triangle_count() << " triangles) but should not have";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), file) << e.what();
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    EXPECT_NE(e.detail().find(words), std::string::npos) << e.what();
    if (line >= 0) {
      EXPECT_EQ(e.line(), line) << e.what();
    }
    return e;
  }
  return Error("no error");
}

class Malformed : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto data = test::shared_data_dir();
    if (!data) GTEST_SKIP() << "../shared/data is absent: skipping real-file test";
    data_ = *data;
    scratch_ = test::scratch_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  std::filesystem::path data_, scratch_;
};

TEST_F(Malformed, VrmlCutInHalfNamesTheLineWhereItEnds) {
  const std::string text = read_bytes(data_ / "vrml/castle_teapot.wrl");
  const auto file = write_bytes(scratch_ / "teapot_cut.wrl", text.substr(0, text.size() / 2));
  const Error e = expect_load_error(file, "is it truncated?");
  EXPECT_GT(e.line(), 50);
}

TEST_F(Malformed, VrmlCoordIndexOutOfRangeIsCaughtBeforeCoinUsesIt) {
  const std::string text = read_bytes(data_ / "vrml/castle_teapot.wrl");
  const auto file =
      write_bytes(scratch_ / "teapot_bad_index.wrl", replace_token_after(text, "coordIndex [", "99999"));
  expect_load_error(file, "coordIndex[0] is 99999, but Coordinate.point has 1563 entries");
}

TEST_F(Malformed, VrmlCoordIndexJustPastTheEndIsAnError) {
  const std::string text = read_bytes(data_ / "vrml/castle_teapot.wrl");
  const auto file =
      write_bytes(scratch_ / "teapot_one_past.wrl", replace_token_after(text, "coordIndex [", "1563"));
  expect_load_error(file,
                    "coordIndex[0] is 1563, but Coordinate.point has 1563 entries (valid: 0..1562 or -1)");
}

TEST_F(Malformed, VrmlNegativeIndexOtherThanTheSeparatorIsAnError) {
  const std::string text = read_bytes(data_ / "vrml/castle_teapot.wrl");
  const auto file =
      write_bytes(scratch_ / "teapot_negative.wrl", replace_token_after(text, "coordIndex [", "-7"));
  expect_load_error(file, "coordIndex[0] is -7");
}

TEST_F(Malformed, VrmlNanCoordinateNamesItsLine) {
  const std::string text = read_bytes(data_ / "vrml/castle_teapot.wrl");
  // The first coordinate, on line 59, becomes NaN.
  const auto file = write_bytes(scratch_ / "teapot_nan.wrl", replace_token_after(text, "point [", "nan"));
  expect_load_error(file, "Couldn't read value for field \"point\"", 59);
}

TEST_F(Malformed, VrmlInfiniteCoordinateIsRefusedNotReplacedByZero) {
  const std::string text = read_bytes(data_ / "vrml/castle_teapot.wrl");
  const auto file = write_bytes(scratch_ / "teapot_inf.wrl", replace_token_after(text, "point [", "1e39"));
  expect_load_error(file, "NaN, infinite or out of float range", 59);
}

TEST_F(Malformed, EmptyFile) {
  expect_load_error(write_bytes(scratch_ / "empty.wrl", ""), "file is empty");
}

TEST_F(Malformed, RandomBytesUnderAVrmlName) {
  std::mt19937 random(7);
  std::string bytes(4096, '\0');
  for (char& b : bytes) b = static_cast<char>(random());
  bytes[0] = 'x';  // not the gzip magic
  const Error e = expect_load_error(write_bytes(scratch_ / "garbage.wrl", bytes), "Expected '{'");
  EXPECT_GT(e.line(), 0) << e.what();
}

TEST_F(Malformed, GzipCutInHalf) {
  const std::string bytes = read_bytes(data_ / "vrml/castle_regular_labirynth_chinchilla.wrl.gz");
  expect_load_error(write_bytes(scratch_ / "cut.wrl.gz", bytes.substr(0, bytes.size() / 2)),
                    "gzip data ends early");
}

TEST_F(Malformed, GzipWithCorruptBytes) {
  std::string bytes = read_bytes(data_ / "vrml/castle_regular_labirynth_chinchilla.wrl.gz");
  for (std::size_t i = 1000; i < 1100; ++i) bytes[i] = static_cast<char>(bytes[i] ^ 0x55);
  expect_load_error(write_bytes(scratch_ / "corrupt.wrl.gz", bytes), "corrupt gzip data");
}

TEST_F(Malformed, UnknownFieldIsAnErrorWithItsLineWhenTheLenientPassIsOff) {
  LoadParams strict;
  strict.drop_unknown_fields = false;
  try {
    load_model(data_ / "vrml/castle_alien_mirror.wrl", strict);
    FAIL() << "loaded";
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 112);
    EXPECT_EQ(e.detail(), "Unknown field \"mirror\" in \"VRMLMaterial\"");
  }
}

TEST_F(Malformed, CoinPrintsNothingOnStderr) {
  const std::string text = read_bytes(data_ / "vrml/castle_teapot.wrl");
  const auto file = write_bytes(scratch_ / "teapot_cut.wrl", text.substr(0, text.size() / 3));
  ::testing::internal::CaptureStderr();
  EXPECT_THROW(load_model(file), Error);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST_F(Malformed, ObjFaceIndexOutOfRange) {
  const std::string text = read_bytes(data_ / "canonical/odedstein_armadillo.obj");
  const auto file = write_bytes(scratch_ / "bad_face.obj", replace_line_after(text, "\nf ", "1 2 99999999"));
  expect_load_error(file, "vertex index out of range");
}

TEST_F(Malformed, ObjNanCoordinate) {
  const std::string text = read_bytes(data_ / "canonical/odedstein_armadillo.obj");
  const auto file = write_bytes(scratch_ / "nan.obj", replace_line_after(text, "\nv ", "nan 0 0"));
  expect_load_error(file, "non-finite coordinate (NaN or Inf)");
}

TEST_F(Malformed, ObjWithoutFaces) {
  const std::string text = read_bytes(data_ / "canonical/odedstein_armadillo.obj");
  std::string vertices_only;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("f ", 0) != 0) vertices_only += line + "\n";
  }
  expect_load_error(write_bytes(scratch_ / "no_faces.obj", vertices_only), "contains no faces");
}

TEST_F(Malformed, PlyCutInHalfIsAnErrorNotAnAbort) {
  const std::string bytes = read_bytes(data_ / "canonical/bun_zipper.ply");
  expect_load_error(write_bytes(scratch_ / "cut.ply", bytes.substr(0, bytes.size() / 2)), "assimp");
}

TEST_F(Malformed, PlyFaceIndexOutOfRange) {
  const std::string text = read_bytes(data_ / "canonical/bun_zipper.ply");
  // The first face line ("3 a b c") gets an index past the 35,947 vertices.
  const auto file = write_bytes(scratch_ / "bad_face.ply", replace_token_after(text, "\n3 ", "999999"));
  expect_load_error(file, "mIndices[0] is out of range");
}

TEST_F(Malformed, GiftiCutInHalfNamesTheXmlLine) {
  const std::string bytes = read_bytes(data_ / "surfaces/spm12_scalp_2562.surf.gii");
  const Error e = expect_load_error(write_bytes(scratch_ / "cut.surf.gii", bytes.substr(0, bytes.size() / 2)),
                                    "malformed GIfTI XML");
  EXPECT_GT(e.line(), 0);
}

TEST_F(Malformed, GzippedGiftiCutInHalf) {
  const std::string bytes = read_bytes(data_ / "surfaces/fsaverage5_pial_left.gii.gz");
  expect_load_error(write_bytes(scratch_ / "cut.gii.gz", bytes.substr(0, bytes.size() / 2)),
                    "gzip data ends early");
}

TEST_F(Malformed, GiftiWithCorruptBase64) {
  std::string text = read_bytes(data_ / "surfaces/spm12_scalp_2562.surf.gii");
  const std::size_t data = text.find("<Data>");
  ASSERT_NE(data, std::string::npos);
  text.replace(data + 6, 4, "!!!!");  // the first four base64 characters of the first array
  const auto file = write_bytes(scratch_ / "bad_data.surf.gii", text);
  const Error e = expect_load_error(file, "GIfTI data array is not valid base64");
  EXPECT_GT(e.line(), 1);
}

TEST(LoadErrors, MissingFileFolderAndUnknownExtension) {
  const auto scratch = test::scratch_dir("LoadErrorsMissing");
  expect_load_error(scratch / "absent.wrl", "no such file");
  expect_load_error(scratch, "is a folder");
  expect_load_error(write_bytes(scratch / "notes.txt", "hello"), "unknown model format '.txt'");
  expect_load_error(write_bytes(scratch / "head.nii", "not really a volume"), "is a volume image");
}

}  // namespace
}  // namespace palpate
