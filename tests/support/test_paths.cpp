#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace palpate::test {

std::filesystem::path source_dir() {
  return PALPATE_SOURCE_DIR;
}
std::filesystem::path binary_dir() {
  return PALPATE_BINARY_DIR;
}

std::optional<std::filesystem::path> shared_data_dir() {
  if (const char* env = std::getenv("PALPATE_SHARED_DATA"); env && *env) {
    if (std::filesystem::is_directory(env)) return std::filesystem::path(env);
    return std::nullopt;
  }
  // The checkout sits beside ../shared; a worktree elsewhere may find it one level further up.
  for (auto dir = source_dir(); dir.has_relative_path(); dir = dir.parent_path()) {
    auto candidate = dir.parent_path() / "shared" / "data";
    if (std::filesystem::is_regular_file(candidate / "manifest.tsv")) return candidate;
  }
  return std::nullopt;
}

std::filesystem::path scratch_dir(const std::string& name) {
  // Under the running test's own folder: ctest runs tests in parallel processes, and a folder shared by
  // two tests would be emptied under one by the other.
  auto dir = binary_dir() / "test-scratch";
  if (const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info()) {
    dir /= std::string(test->test_suite_name()) + "." + test->name();
  } else if (const ::testing::TestSuite* suite = ::testing::UnitTest::GetInstance()->current_test_suite()) {
    dir /= suite->name();
  }
  dir /= name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace palpate::test
