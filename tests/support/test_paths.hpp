#pragma once
// Where tests find the project's files and the shared third-party data.
#include <filesystem>
#include <optional>

namespace palpate::test {

std::filesystem::path source_dir();
std::filesystem::path binary_dir();
// ../shared/data beside the checkout (or $PALPATE_SHARED_DATA); empty when absent, so tests can skip.
std::optional<std::filesystem::path> shared_data_dir();
// A fresh, empty folder for the running test's output files (unique to that test).
std::filesystem::path scratch_dir(const std::string& name);

}  // namespace palpate::test

// Skips the current test with a message when ../shared/data is absent.
#define PALPATE_REQUIRE_SHARED_DATA(var)                                               \
  const auto var##_opt = ::palpate::test::shared_data_dir();                           \
  if (!var##_opt) GTEST_SKIP() << "../shared/data is absent: skipping real-file test"; \
  const std::filesystem::path var = *var##_opt
