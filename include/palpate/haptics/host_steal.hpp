#pragma once
// Time the hypervisor gave this virtual machine's CPUs to others ("steal", from /proc/stat): a haptic
// thread that misses its deadline while the host ran something else is not late by its own doing, and
// reports separate the two. Reads a file: never on the haptic thread.
#include <optional>

namespace palpate {

// The machine's total steal time since boot, in milliseconds, summed over its CPUs; none where
// /proc/stat is missing or has no steal column (not Linux, or a kernel before 2.6.11).
std::optional<double> host_steal_ms();

}  // namespace palpate
