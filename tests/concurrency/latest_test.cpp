// Latest<T> under one writer and several readers: every value read was written whole by one store, a
// reader never sees the version go back, the readers really did read while stores were under way (or
// the test could not have seen a torn value), and neither side allocates.
#include "palpate/haptics/latest.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "allocation_counter.hpp"

namespace palpate {
namespace {

// A value with internal redundancy: every word is a different function of the serial, so a read
// that mixes two stores cannot pass check().
struct Redundant {
  std::uint64_t serial = 0;
  std::array<std::uint64_t, 63> words{};  // 512 bytes: a wide window for a torn read to show
};

Redundant make_redundant(std::uint64_t serial) {
  Redundant value;
  value.serial = serial;
  for (std::size_t i = 0; i < value.words.size(); ++i)
    value.words[i] = (serial + i) * 0x9E3779B97F4A7C15ull ^ (i << 40);
  return value;
}

bool whole(const Redundant& value) {
  const Redundant expected = make_redundant(value.serial);
  return value.words == expected.words;
}

TEST(LatestTest, CheckRejectsAMixOfTwoValues) {
  Redundant mixed = make_redundant(7);
  mixed.words[5] = make_redundant(8).words[5];
  EXPECT_FALSE(whole(mixed));
  EXPECT_TRUE(whole(make_redundant(8)));
}

TEST(LatestTest, LoadReturnsTheLastStoreAndCountsVersions) {
  Latest<Redundant> channel(make_redundant(1));
  EXPECT_EQ(channel.version(), 0u);
  EXPECT_EQ(channel.load().serial, 1u);
  channel.store(make_redundant(2));
  channel.store(make_redundant(3));
  EXPECT_EQ(channel.version(), 2u);
  const Redundant got = channel.load();
  EXPECT_EQ(got.serial, 3u);
  EXPECT_TRUE(whole(got));
}

TEST(LatestTest, ReadersNeverSeeATornOrOlderValueUnderAConcurrentWriter) {
  // No more threads than cores: a reader waiting for a time slice overlaps nothing.
  const int reader_count = int(std::clamp(std::thread::hardware_concurrency(), 2u, 4u)) - 1;
  // Each reader must see the value change under it this often (reads and stores interleaving), or a
  // torn read could not have shown; the writer stores until they have, however the threads are scheduled.
  constexpr std::uint64_t wanted_changes = 5000;
  Latest<Redundant> channel(make_redundant(0));
  std::atomic<bool> done{false};
  struct ReaderResult {
    std::uint64_t reads = 0, torn = 0, backwards = 0, last = 0;
    std::atomic<std::uint64_t> changes{0};
  };
  std::vector<ReaderResult> results(reader_count);
  std::vector<std::thread> readers;
  for (int r = 0; r < reader_count; ++r) {
    readers.emplace_back([&, r] {
      ReaderResult& result = results[std::size_t(r)];
      // Read at least until the writer is done, and once more after.
      for (bool finished = false; !finished;) {
        finished = done.load(std::memory_order_acquire);
        const Redundant value = channel.load();
        ++result.reads;
        if (!whole(value)) ++result.torn;
        if (value.serial < result.last) ++result.backwards;
        if (value.serial != result.last) result.changes.fetch_add(1, std::memory_order_relaxed);
        result.last = value.serial;
      }
    });
  }
  std::uint64_t stores = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  std::thread writer([&] {
    const auto enough = [&] {
      return std::all_of(results.begin(), results.end(), [&](const ReaderResult& result) {
        return result.changes.load(std::memory_order_relaxed) >= wanted_changes;
      });
    };
    const auto changes_seen = [&] {
      std::uint64_t sum = 0;
      for (const ReaderResult& result : results) sum += result.changes.load(std::memory_order_relaxed);
      return sum;
    };
    while ((stores % 1024 != 0 || !enough()) && std::chrono::steady_clock::now() < until) {
      // Paced like the haptic loop: a store, then a moment for the readers to take it. Stores back to
      // back starve a seqlock's readers (under ThreadSanitizer a 512-byte read hardly ever completed
      // between two: 580 changes in 60 s on the CI machine).
      const std::uint64_t seen = changes_seen();
      channel.store(make_redundant(++stores));
      const auto pause_until = std::chrono::steady_clock::now() + std::chrono::microseconds(50);
      while (changes_seen() == seen && std::chrono::steady_clock::now() < pause_until)
        std::this_thread::yield();
    }
    done.store(true, std::memory_order_release);
  });
  writer.join();
  for (std::thread& reader : readers) reader.join();
  for (const ReaderResult& result : results) {
    EXPECT_EQ(result.torn, 0u);
    EXPECT_EQ(result.backwards, 0u);
    EXPECT_GE(result.changes.load(), wanted_changes) << "the reader hardly overlapped the writer";
    EXPECT_EQ(result.last, stores) << "the last read after the writer finished sees the last store";
  }
  EXPECT_EQ(channel.version(), stores);
}

// try_load never waits: while a writer stores without pause, some attempts find a store under way and
// say so (false) rather than wait, and every attempt that succeeds holds a whole value.
TEST(LatestTest, TryLoadReportsAStoreUnderWayInsteadOfWaiting) {
  Latest<Redundant> channel(make_redundant(0));
  std::atomic<bool> done{false};
  std::thread writer([&] {
    for (std::uint64_t serial = 1; !done.load(std::memory_order_relaxed); ++serial) {
      channel.store(make_redundant(serial));
    }
  });
  std::uint64_t refused = 0, torn = 0;
  Redundant out;
  for (int attempt = 0; attempt < 2'000'000 && refused < 100; ++attempt) {
    if (!channel.try_load(out)) {
      ++refused;
    } else if (!whole(out)) {
      ++torn;
    }
  }
  done.store(true, std::memory_order_relaxed);
  writer.join();
  EXPECT_GT(refused, 0u) << "no attempt overlapped a store";
  EXPECT_EQ(torn, 0u);
}

TEST(LatestTest, StoreAndLoadNeverAllocate) {
  Latest<Redundant> channel(make_redundant(0));
  test::count_allocations_on_this_thread();
  const std::uint64_t before = test::counted_allocations();
  std::uint64_t sum = 0;
  for (std::uint64_t serial = 1; serial <= 10'000; ++serial) {
    channel.store(make_redundant(serial));
    sum += channel.load().serial;
  }
  EXPECT_EQ(test::counted_allocations(), before);
  EXPECT_EQ(sum, 10'000u * 10'001u / 2u);
}

TEST(LatestTest, TryLoadSucceedsWhenNoStoreIsUnderWay) {
  Latest<Redundant> channel(make_redundant(4));
  Redundant out;
  ASSERT_TRUE(channel.try_load(out));
  EXPECT_EQ(out.serial, 4u);
  EXPECT_TRUE(whole(out));
}

}  // namespace
}  // namespace palpate
