#pragma once
// Number formatting for the printed tables.
#include <cstddef>
#include <string>

namespace palpate::cli {

// 159063 -> "159,063"
std::string with_thousands(std::size_t n);

}  // namespace palpate::cli
