#pragma once
// Whole-file reading for the model loaders, with gzip detected by its magic bytes (1f 8b), not by
// the file name. Setup code: allocates, throws palpate::Error naming the file.
#include <filesystem>
#include <string>

namespace palpate::detail {

struct FileBytes {
  std::string bytes;  // the file's content, decompressed when it was gzip
  bool was_gzip = false;
};

// Throws for a missing file, a folder, an unreadable or empty file, and corrupt or truncated gzip.
FileBytes read_file_bytes(const std::filesystem::path& file);

// True when `bytes` starts with the gzip magic bytes.
bool is_gzip(const std::string& bytes) noexcept;

// Inflates every gzip member of `compressed` (concatenated members are one stream by RFC 1952).
std::string gunzip(const std::string& compressed, const std::filesystem::path& file);

}  // namespace palpate::detail
