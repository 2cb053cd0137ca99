// The renderer's side thread: a task runs on another thread, what it wrote is there to read once wait()
// returns, a task handed while one runs starts after it, and the thread is not stopped under a task.
#include "gl/side_thread.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "allocation_counter.hpp"

namespace palpate::gl {
namespace {

using namespace std::chrono_literals;

TEST(SideThread, RunsEachTaskOnAnotherThreadAndItsWritesAreThereAfterWait) {
  SideThread side;
  std::vector<std::uint64_t> written(100'000);
  std::thread::id ran_on;
  for (std::uint64_t round = 1; round <= 50; ++round) {
    side.start([&, round] {
      ran_on = std::this_thread::get_id();
      for (std::size_t i = 0; i < written.size(); ++i) written[i] = round * 1'000'003 + i;
    });
    side.wait();
    EXPECT_NE(ran_on, std::this_thread::get_id());
    for (std::size_t i = 0; i < written.size(); i += 9'973) ASSERT_EQ(written[i], round * 1'000'003 + i) << i;
    ASSERT_EQ(written.back(), round * 1'000'003 + written.size() - 1);
  }
}

TEST(SideThread, ATaskHandedWhileOneRunsStartsAfterIt) {
  SideThread side;
  int first_done = 0, seen_by_second = -1;
  side.start([&] {
    std::this_thread::sleep_for(30ms);
    first_done = 1;
  });
  side.start([&] { seen_by_second = first_done; });
  side.wait();
  EXPECT_EQ(seen_by_second, 1);
}

TEST(SideThread, ItsEndRunsTheTaskInHandFirst) {
  for (int round = 0; round < 20; ++round) {
    bool done = false;
    {
      SideThread side;
      side.start([&] { done = true; });  // ended at once, most often before the thread has woken
    }
    ASSERT_TRUE(done) << round;
  }
}

TEST(SideThread, HandingItASmallTaskAllocatesNothingOnEitherThread) {
  SideThread side;
  int value = 0;
  side.start([] { test::count_allocations_on_this_thread(); });
  side.wait();
  test::count_allocations_on_this_thread();
  const std::uint64_t before = test::counted_allocations();
  for (int i = 0; i < 100; ++i) {
    side.start([&value] { ++value; });  // the renderer's task holds one reference, as this one does
    side.wait();
  }
  EXPECT_EQ(test::counted_allocations() - before, 0u);
  EXPECT_EQ(value, 100);
}

}  // namespace
}  // namespace palpate::gl
