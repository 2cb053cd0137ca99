#include "palpate/core/error.hpp"

namespace palpate {
namespace {

std::string format(const std::filesystem::path& file, int line, const std::string& detail) {
  std::string out;
  if (!file.empty()) {
    out.append(file.string());
    if (line > 0) out.append(":").append(std::to_string(line));
    out.append(": ");
  }
  out.append(detail);
  return out;
}

}  // namespace

Error::Error(std::filesystem::path file, int line, std::string detail)
    : std::runtime_error(format(file, line, detail)),
      file_(std::move(file)),
      line_(line),
      detail_(std::move(detail)) {}

}  // namespace palpate
