// Latest<T> under one writer and several readers: every value read was written whole by one store,
// and a reader never sees the version go back.
#include "palpate/haptics/latest.hpp"

#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

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
  constexpr std::uint64_t stores = 500'000;
  constexpr int reader_count = 3;
  Latest<Redundant> channel(make_redundant(0));
  std::atomic<bool> done{false};
  struct ReaderResult {
    std::uint64_t reads = 0, torn = 0, backwards = 0, distinct = 0;
  };
  std::vector<ReaderResult> results(reader_count);
  std::vector<std::thread> readers;
  for (int r = 0; r < reader_count; ++r) {
    readers.emplace_back([&, r] {
      ReaderResult& result = results[std::size_t(r)];
      std::uint64_t last = 0;
      // Read at least until the writer is done, and once more after.
      for (bool finished = false; !finished;) {
        finished = done.load(std::memory_order_acquire);
        const Redundant value = channel.load();
        ++result.reads;
        if (!whole(value)) ++result.torn;
        if (value.serial < last) ++result.backwards;
        if (value.serial != last) ++result.distinct;
        last = value.serial;
      }
      EXPECT_EQ(last, stores) << "the last read after the writer finished sees the last store";
    });
  }
  std::thread writer([&] {
    for (std::uint64_t serial = 1; serial <= stores; ++serial) channel.store(make_redundant(serial));
    done.store(true, std::memory_order_release);
  });
  writer.join();
  for (std::thread& reader : readers) reader.join();
  for (const ReaderResult& result : results) {
    EXPECT_EQ(result.torn, 0u);
    EXPECT_EQ(result.backwards, 0u);
    EXPECT_GT(result.reads, 0u);
  }
  EXPECT_EQ(channel.version(), stores);
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
