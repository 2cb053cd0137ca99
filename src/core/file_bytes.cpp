#include "core/file_bytes.hpp"

#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "palpate/core/error.hpp"

namespace palpate::detail {

bool is_gzip(const std::string& bytes) noexcept {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gunzip(const std::string& compressed, const std::filesystem::path& file) {
  z_stream stream{};
  // 16 + MAX_WBITS: expect a gzip header and trailer (CRC and length are checked by zlib).
  if (inflateInit2(&stream, 16 + MAX_WBITS) != Z_OK) throw Error(file, 0, "zlib could not start inflating");
  std::string out;
  out.resize(compressed.size() * 4 + 1024);
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = static_cast<uInt>(compressed.size());
  int status = Z_OK;
  for (;;) {
    if (stream.total_out >= out.size()) out.resize(out.size() * 2);
    stream.next_out = reinterpret_cast<Bytef*>(out.data() + stream.total_out);
    stream.avail_out = static_cast<uInt>(out.size() - stream.total_out);
    status = inflate(&stream, Z_NO_FLUSH);
    if (status == Z_STREAM_END) {
      // Another member may follow; anything else after the trailer is trailing garbage we ignore,
      // as gzip(1) does.
      if (stream.avail_in >= 2 && stream.next_in[0] == 0x1f && stream.next_in[1] == 0x8b) {
        inflateReset(&stream);
        continue;
      }
      break;
    }
    if (status == Z_OK) continue;
    if (status == Z_BUF_ERROR && stream.avail_out == 0) continue;  // output full: grow and go on
    if (status == Z_BUF_ERROR) {
      const auto consumed = stream.total_in;
      inflateEnd(&stream);
      throw Error(
          file, 0,
          "gzip data ends early after " + std::to_string(consumed) + " compressed bytes (truncated file?)");
    }
    const std::string reason = stream.msg ? stream.msg : zError(status);
    inflateEnd(&stream);
    throw Error(file, 0, "corrupt gzip data: " + reason);
  }
  out.resize(stream.total_out);
  inflateEnd(&stream);
  return out;
}

FileBytes read_file_bytes(const std::filesystem::path& file) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) throw Error(file, 0, "no such file");
  if (std::filesystem::is_directory(status)) throw Error(file, 0, "is a folder, not a model file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file, 0, std::string("cannot open: ") + std::strerror(errno));
  FileBytes result;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size < 0) throw Error(file, 0, "cannot tell its size");
  result.bytes.resize(static_cast<std::size_t>(size));
  in.read(result.bytes.data(), size);
  if (in.gcount() != size) throw Error(file, 0, "read error");
  if (result.bytes.empty()) throw Error(file, 0, "file is empty (0 bytes)");
  if (is_gzip(result.bytes)) {
    result.bytes = gunzip(result.bytes, file);
    result.was_gzip = true;
    if (result.bytes.empty()) throw Error(file, 0, "gzip data decompresses to nothing (0 bytes)");
  }
  return result;
}

}  // namespace palpate::detail
