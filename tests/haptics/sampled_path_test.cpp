// SampledPath interpolation and the CSV reader with its errors (file and line named).
#include "palpate/haptics/sampled_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "palpate/core/error.hpp"
#include "palpate/haptics/scripted_device.hpp"
#include "test_paths.hpp"

namespace palpate {
namespace {

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = test::scratch_dir("sampled_path_" + name) / (name + ".csv");
  std::ofstream(path) << text;
  return path;
}

// The Error a CSV raises, as "line: detail", or "no error".
std::string csv_error(const std::string& name, const std::string& text) {
  const auto path = write_file(name, text);
  try {
    load_path_csv(path);
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << "what() names the file";
    return std::to_string(e.line()) + ": " + e.detail();
  }
  return "no error";
}

TEST(SampledPathTest, InterpolatesLinearlyAndHoldsTheEnds) {
  const SampledPath path({{1.0, {0, 0, 0}}, {2.0, {10, 0, 0}}, {4.0, {10, 20, -4}}});
  EXPECT_EQ(path.start_s(), 1.0);
  EXPECT_EQ(path.end_s(), 4.0);
  const DeviceState mid = path.sample(1.25);
  EXPECT_FLOAT_EQ(mid.position_mm.x, 2.5f);
  EXPECT_FLOAT_EQ(mid.velocity_mm_per_s.x, 10.0f);
  const DeviceState later = path.sample(3.5);
  EXPECT_FLOAT_EQ(later.position_mm.y, 15.0f);
  EXPECT_FLOAT_EQ(later.position_mm.z, -3.0f);
  EXPECT_FLOAT_EQ(later.velocity_mm_per_s.y, 10.0f);
  EXPECT_FLOAT_EQ(later.velocity_mm_per_s.z, -2.0f);
  // At a sample the segment that starts there gives the velocity.
  EXPECT_FLOAT_EQ(path.sample(2.0).position_mm.x, 10.0f);
  EXPECT_FLOAT_EQ(path.sample(2.0).velocity_mm_per_s.y, 10.0f);
  EXPECT_EQ(path.sample(0.0).position_mm, glm::vec3(0.0f));
  EXPECT_EQ(path.sample(0.0).velocity_mm_per_s, glm::vec3(0.0f));
  EXPECT_EQ(path.sample(9.0).position_mm, glm::vec3(10, 20, -4));
  EXPECT_EQ(path.sample(9.0).velocity_mm_per_s, glm::vec3(0.0f));
}

TEST(SampledPathTest, RejectsUnorderedOrNonFiniteSamples) {
  EXPECT_THROW(SampledPath({}), Error);
  EXPECT_THROW(SampledPath({{0.0, {0, 0, 0}}, {0.0, {1, 0, 0}}}), Error);
  EXPECT_THROW(SampledPath({{0.0, {0, 0, 0}}, {1.0, {std::nanf(""), 0, 0}}}), Error);
}

TEST(SampledPathCsvTest, ReadsHeaderCommentsBlankLinesAndCrlf) {
  const auto file = write_file("good",
                               "# a path\r\n"
                               "t,x,y,z\r\n"
                               "0, 0, 0, 10\r\n"
                               "\r\n"
                               "0.5,5,0,0\r\n"
                               "1.0 , 5 , -5 , 0\n");
  const SampledPath path = load_path_csv(file);
  ASSERT_EQ(path.samples().size(), 3u);
  EXPECT_FLOAT_EQ(path.sample(0.25).position_mm.x, 2.5f);
  EXPECT_FLOAT_EQ(path.sample(0.25).position_mm.z, 5.0f);
  EXPECT_FLOAT_EQ(path.sample(0.75).position_mm.y, -2.5f);
  ScriptedDevice device(path);
  EXPECT_FLOAT_EQ(device.read(0.75).velocity_mm_per_s.y, -10.0f);
}

TEST(SampledPathCsvTest, ErrorsNameTheLineAndWhatIsWrong) {
  EXPECT_EQ(csv_error("short", "t,x,y,z\n0,0,0,0\n1,2,3\n"),
            "3: expected 4 comma-separated values t,x,y,z, got 3");
  EXPECT_EQ(csv_error("long", "0,0,0,0,9\n"), "1: expected 4 comma-separated values t,x,y,z, got 5");
  EXPECT_EQ(csv_error("word", "0,0,0,0\n\n1,abc,0,0\n"), "3: x: 'abc' is not a number");
  EXPECT_EQ(csv_error("empty_field", "0,0,,0\n"), "1: y: '' is not a number");
  EXPECT_EQ(csv_error("trailing", "0,0,0,1mm\n"), "1: z: '1mm' is not a number");
  EXPECT_EQ(csv_error("nan", "0,0,0,0\n1,nan,0,0\n"), "2: x is not finite: 'nan'");
  EXPECT_EQ(csv_error("inf", "inf,0,0,0\n"), "1: t is not finite: 'inf'");
  EXPECT_EQ(csv_error("backwards", "0,0,0,0\n1,0,0,0\n1,1,0,0\n"),
            "3: t = 1.000000 s is not after the previous sample's 1.000000 s");
  EXPECT_EQ(csv_error("header_only", "t,x,y,z\n# nothing\n"), "2: no samples (expected lines t,x,y,z)");
  EXPECT_EQ(csv_error("late_header", "0,0,0,0\nt,x,y,z\n"), "2: t: 't' is not a number");
}

TEST(SampledPathCsvTest, MissingFileIsAnErrorNamingIt) {
  const auto missing = test::scratch_dir("sampled_path_missing") / "absent.csv";
  try {
    load_path_csv(missing);
    FAIL() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), missing);
    EXPECT_NE(e.detail().find("cannot open"), std::string::npos);
  }
}

}  // namespace
}  // namespace palpate
