#include "palpate/haptics/sampled_path.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

#include "palpate/core/error.hpp"
#include "palpate/core/finite.hpp"

namespace palpate {
namespace {

bool finite(const PathSample& s) {
  return std::isfinite(s.time_s) && is_finite(s.position_mm);
}

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

}  // namespace

SampledPath::SampledPath(std::vector<PathSample> samples) : samples_(std::move(samples)) {
  if (samples_.empty()) throw Error("sampled path: no samples");
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    if (!finite(samples_[i])) throw Error("sampled path: sample " + std::to_string(i) + " is not finite");
    if (i > 0 && !(samples_[i].time_s > samples_[i - 1].time_s)) {
      throw Error("sampled path: sample " + std::to_string(i) +
                  " at t = " + std::to_string(samples_[i].time_s) + " s is not after the previous one at " +
                  std::to_string(samples_[i - 1].time_s) + " s");
    }
  }
}

DeviceState SampledPath::sample(double time_s) const noexcept {
  DeviceState state;
  if (!(time_s > samples_.front().time_s)) {
    state.position_mm = samples_.front().position_mm;
    return state;
  }
  if (time_s >= samples_.back().time_s) {
    state.position_mm = samples_.back().position_mm;
    return state;
  }
  // First sample after time_s; the segment [next - 1, next) contains it.
  const auto next = std::upper_bound(samples_.begin(), samples_.end(), time_s,
                                     [](double t, const PathSample& s) { return t < s.time_s; });
  const PathSample& a = *(next - 1);
  const PathSample& b = *next;
  const double span = b.time_s - a.time_s;
  const auto w = static_cast<float>((time_s - a.time_s) / span);
  state.position_mm = a.position_mm + (b.position_mm - a.position_mm) * w;
  state.velocity_mm_per_s = (b.position_mm - a.position_mm) / static_cast<float>(span);
  return state;
}

SampledPath load_path_csv(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(file, 0, "cannot open the path file");
  std::vector<PathSample> samples;
  std::string line;
  int line_number = 0;
  static constexpr const char* names[] = {"t", "x", "y", "z"};
  while (std::getline(in, line)) {
    ++line_number;
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    if (samples.empty() && text == "t,x,y,z") continue;
    double values[4];
    std::size_t count = 0;
    std::size_t begin = 0;
    while (true) {
      const std::size_t comma = text.find(',', begin);
      const std::string_view field =
          trim(text.substr(begin, comma == std::string_view::npos ? text.npos : comma - begin));
      if (count < 4) {
        const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), values[count]);
        if (field.empty() || error != std::errc() || end != field.data() + field.size()) {
          throw Error(file, line_number,
                      std::string(names[count]) + ": '" + std::string(field) + "' is not a number");
        }
        if (!std::isfinite(values[count])) {
          throw Error(file, line_number,
                      std::string(names[count]) + " is not finite: '" + std::string(field) + "'");
        }
      }
      ++count;
      if (comma == std::string_view::npos) break;
      begin = comma + 1;
    }
    if (count != 4) {
      throw Error(file, line_number,
                  "expected 4 comma-separated values t,x,y,z, got " + std::to_string(count));
    }
    if (!samples.empty() && !(values[0] > samples.back().time_s)) {
      throw Error(file, line_number,
                  "t = " + std::to_string(values[0]) + " s is not after the previous sample's " +
                      std::to_string(samples.back().time_s) + " s");
    }
    samples.push_back({values[0], glm::vec3(float(values[1]), float(values[2]), float(values[3]))});
  }
  if (samples.empty()) throw Error(file, line_number, "no samples (expected lines t,x,y,z)");
  return SampledPath(std::move(samples));
}

}  // namespace palpate
