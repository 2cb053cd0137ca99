#include "format.hpp"

#include <cstdio>
#include <fstream>

#include "palpate/core/error.hpp"

namespace palpate::cli {

std::string with_thousands(std::size_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

nlohmann::json percentiles_json(const Percentiles& p) {
  return {{"p50", p.p50}, {"p99", p.p99}, {"p999", p.p999}, {"max", p.max}};
}

void write_json_file(const std::filesystem::path& file, const nlohmann::json& document) {
  std::ofstream out(file);
  if (!out) throw Error(file, 0, "cannot open the JSON report for writing");
  out << document.dump(2) << '\n';
  out.close();
  if (!out) throw Error(file, 0, "writing the JSON report failed (disk full?)");
  std::printf("wrote %s\n", file.string().c_str());
}

}  // namespace palpate::cli
