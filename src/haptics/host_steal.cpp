#include "palpate/haptics/host_steal.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace palpate {

std::optional<double> host_steal_ms() {
  std::ifstream stat("/proc/stat");
  std::string line;
  if (!stat || !std::getline(stat, line) || !line.starts_with("cpu ")) return std::nullopt;
  // cpu  user nice system idle iowait irq softirq steal ...  (in clock ticks)
  std::istringstream fields(line.substr(4));
  unsigned long long value = 0, steal = 0;
  int column = 0;
  while (column < 8 && fields >> value) {
    if (++column == 8) steal = value;
  }
  if (column < 8) return std::nullopt;
  const long ticks_per_second = sysconf(_SC_CLK_TCK);
  if (ticks_per_second <= 0) return std::nullopt;
  return double(steal) * 1000.0 / double(ticks_per_second);
}

}  // namespace palpate
