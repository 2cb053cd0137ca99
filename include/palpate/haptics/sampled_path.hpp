#pragma once
// A tool-tip path given as timed samples, interpolated linearly in time; read from a CSV file
// `t,x,y,z` (seconds, device-frame mm) or built in code. Construction allocates and may throw;
// sample() is noexcept and allocation-free (a binary search), so it can run in the haptic tick.
#include <filesystem>
#include <glm/vec3.hpp>
#include <vector>

#include "palpate/haptics/device.hpp"

namespace palpate {

struct PathSample {
  double time_s = 0.0;
  glm::vec3 position_mm{0.0f};
};

class SampledPath {
 public:
  // Throws palpate::Error for no samples, a non-finite value, or times that do not strictly increase
  // (naming the sample index).
  explicit SampledPath(std::vector<PathSample> samples);

  // Position interpolated at `time_s`, held at the first and last sample outside their range; the
  // velocity is that of the straight segment containing `time_s` (zero outside the range).
  DeviceState sample(double time_s) const noexcept;

  double start_s() const noexcept { return samples_.front().time_s; }
  double end_s() const noexcept { return samples_.back().time_s; }
  const std::vector<PathSample>& samples() const noexcept { return samples_; }

 private:
  std::vector<PathSample> samples_;
};

// Reads a CSV path: one sample `t,x,y,z` per line (whitespace around values allowed), an optional
// header line `t,x,y,z`, blank lines and lines starting with '#' ignored, CRLF accepted. Throws
// palpate::Error naming the file and line for a missing file, a wrong column count, a value that is
// not a number or not finite, a time not after the previous one, or a file without samples.
SampledPath load_path_csv(const std::filesystem::path& file);

}  // namespace palpate
