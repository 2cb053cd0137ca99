#pragma once
// The one exception type of palpate's setup code (loading, parsing, GL setup).
// Real-time functions never throw: they report trouble through flags in their results.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace palpate {

class Error : public std::runtime_error {
 public:
  // `file` may be empty and `line` 0 where they are unknown; what() reads "file:line: detail".
  Error(std::filesystem::path file, int line, std::string detail);
  explicit Error(std::string detail) : Error({}, 0, std::move(detail)) {}

  const std::filesystem::path& file() const noexcept { return file_; }
  int line() const noexcept { return line_; }
  const std::string& detail() const noexcept { return detail_; }

 private:
  std::filesystem::path file_;
  int line_;
  std::string detail_;
};

}  // namespace palpate
