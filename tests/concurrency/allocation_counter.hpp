#pragma once
// Counts heap allocations made by threads that opted in: this test binary replaces the global
// operator new and delete (allocation_counter.cpp) with versions over malloc/free that count.
#include <cstdint>

namespace palpate::test {

// From now on, allocations on the calling thread are counted.
void count_allocations_on_this_thread() noexcept;
// Allocations counted so far on all opted-in threads.
std::uint64_t counted_allocations() noexcept;

}  // namespace palpate::test
