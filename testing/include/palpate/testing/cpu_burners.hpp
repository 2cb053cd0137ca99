#pragma once
// Other processes that keep CPU cores busy while a benchmark runs: forked children spinning at
// normal priority, killed when the CpuBurners object goes (or when this process dies).
#include <sys/types.h>

#include <vector>

namespace palpate::testing {

class CpuBurners {
 public:
  // Forks `count` spinning children. Call it while no other thread of this process runs.
  // Throws palpate::Error when fork fails.
  explicit CpuBurners(int count);
  ~CpuBurners();
  CpuBurners(const CpuBurners&) = delete;
  CpuBurners& operator=(const CpuBurners&) = delete;

 private:
  void kill_all() noexcept;
  std::vector<pid_t> children_;
};

}  // namespace palpate::testing
