#pragma once
// Formatting of figures for the printed tables and the JSON reports.
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "palpate/haptics/loop_statistics.hpp"

namespace palpate::cli {

// 159063 -> "159,063"
std::string with_thousands(std::size_t n);

// {"p50": .., "p99": .., "p999": .., "max": ..}
nlohmann::json percentiles_json(const Percentiles& p);

// Writes `document` (indented) to `file` and says so on stdout; throws palpate::Error naming the file
// when it cannot be written.
void write_json_file(const std::filesystem::path& file, const nlohmann::json& document);

}  // namespace palpate::cli
