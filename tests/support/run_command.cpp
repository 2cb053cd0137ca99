#include "run_command.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace palpate::test {

CommandResult run_command(const std::string& command) {
  CommandResult result;
  const std::filesystem::path err_file =
      std::filesystem::temp_directory_path() / ("palpate-test-stderr-" + std::to_string(getpid()));
  FILE* pipe = popen(("(" + command + ") 2>'" + err_file.string() + "'").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  while (std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe))
    result.out.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ostringstream err;
  err << std::ifstream(err_file).rdbuf();
  result.err = err.str();
  std::filesystem::remove(err_file);
  return result;
}

}  // namespace palpate::test
