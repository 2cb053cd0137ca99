#pragma once
// Formatting of figures for the printed tables and the JSON reports.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "palpate/haptics/loop_statistics.hpp"

namespace palpate::cli {

// 159063 -> "159,063"
std::string with_thousands(std::size_t n);

// {"p50": .., "p99": .., "p999": .., "max": ..}
nlohmann::json percentiles_json(const Percentiles& p);

}  // namespace palpate::cli
