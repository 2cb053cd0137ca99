#pragma once
// Runs a shell command and captures what it printed, stdout and stderr apart, for tests of the palpate
// executable.
#include <string>

namespace palpate::test {

struct CommandResult {
  int exit_status = -1;  // -1 when it did not exit normally
  std::string out;       // stdout
  std::string err;       // stderr
  // Both, for failure messages.
  std::string both() const { return "stdout:\n" + out + "stderr:\n" + err; }
};

CommandResult run_command(const std::string& command);

}  // namespace palpate::test
