#pragma once
// Runs a shell command and captures what it printed, for tests of the palpate executable.
#include <string>

namespace palpate::test {

struct CommandResult {
  int exit_status = -1;
  std::string output;  // stdout and stderr together
};

CommandResult run_command(const std::string& command);

}  // namespace palpate::test
