#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace palpate::cli {

Progress::Progress() : terminal_(isatty(STDERR_FILENO) != 0) {}

Progress::~Progress() {
  if (terminal_ && !current_.empty()) std::fprintf(stderr, "\n");
}

void Progress::update(std::string_view what, std::string_view stage, double fraction) {
  const std::string label = std::string(what) + (what.empty() ? "" : ": ") + std::string(stage);
  const int percent = std::clamp(int(fraction * 100.0), 0, 100);
  if (!terminal_) {  // a line when a stage starts
    if (label != current_) std::fprintf(stderr, "palpate: %s\n", label.c_str());
    current_ = label;
    return;
  }
  if (label == current_ && percent == shown_percent_) return;
  if (label != current_ && !current_.empty()) std::fprintf(stderr, "\n");
  constexpr int width = 30;
  const int filled = percent * width / 100;
  std::fprintf(stderr, "\r%-32s [%.*s%*s] %3d%%", label.c_str(), filled, "##############################",
               width - filled, "", percent);
  std::fflush(stderr);
  current_ = label;
  shown_percent_ = percent;
}

}  // namespace palpate::cli
