#pragma once
// Progress of long stages on stderr: one bar redrawn in place on a terminal, one plain line per stage
// otherwise (logs, pipes, tests).
#include <string>
#include <string_view>

namespace palpate::cli {

class Progress {
 public:
  Progress();
  ~Progress();  // ends the bar's line
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // `what` (an object, a file) at `stage`, `fraction` in [0, 1] done.
  void update(std::string_view what, std::string_view stage, double fraction);

 private:
  bool terminal_;
  std::string current_;  // "what: stage" last shown
  int shown_percent_ = -1;
};

}  // namespace palpate::cli
