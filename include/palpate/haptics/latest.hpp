#pragma once
// Latest<T>: a latest-value channel for one writer and any number of readers, lock-free on both
// sides. The writer never waits; a reader never blocks the writer and always gets a value that one
// store() wrote whole (never a mix of two), retrying while a store is under way.
//
// A seqlock, written for the C++ memory model (Boehm, "Can seqlocks get along with programming
// language memory models?", MSPC 2012): the value lives in an array of std::atomic<uint64_t> words,
// so the racing copy is made of atomic accesses (no data race, no UB, clean under ThreadSanitizer);
// the words are stored with release and loaded with acquire ordering, which orders them after the
// writer's "odd" sequence store and before the reader's second sequence load without standalone
// fences (on x86-64 these are plain moves). Written by hand because it is the product: the
// haptic-to-graphics hand-over of a Contact.
//
// T must be trivially copyable. store() is safe in the haptic tick (no allocation, no lock, no
// system call); only one thread may call store().
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace palpate {

template <class T>
class Latest {
  static_assert(std::is_trivially_copyable_v<T>, "Latest<T> copies T bytewise");
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free, "Latest<T> must never take a lock");

 public:
  Latest() noexcept(std::is_nothrow_default_constructible_v<T>) : Latest(T{}) {}
  explicit Latest(const T& initial) noexcept { write_words(initial, std::memory_order_relaxed); }

  Latest(const Latest&) = delete;
  Latest& operator=(const Latest&) = delete;

  // Writer only.
  void store(const T& value) noexcept {
    const std::uint64_t seq = sequence_.load(std::memory_order_relaxed);
    sequence_.store(seq + 1, std::memory_order_relaxed);  // odd: a store is under way
    write_words(value, std::memory_order_release);        // each ordered after the odd sequence
    sequence_.store(seq + 2, std::memory_order_release);  // even: the value is whole
  }

  // Any thread. Retries while a store is under way; with one store per haptic tick (~100 ns of a
  // millisecond) a retry is rare and short.
  T load() const noexcept {
    T value;
    while (!try_load(value)) {
    }
    return value;
  }

  // Any thread, one attempt: false when a store overlapped, and `out` is then unspecified.
  bool try_load(T& out) const noexcept {
    const std::uint64_t before = sequence_.load(std::memory_order_acquire);
    if (before & 1u) return false;
    std::array<std::uint64_t, word_count> words;
    for (std::size_t i = 0; i < word_count; ++i) words[i] = words_[i].load(std::memory_order_acquire);
    if (sequence_.load(std::memory_order_relaxed) != before) return false;
    std::memcpy(static_cast<void*>(&out), words.data(), sizeof(T));  // T is trivially copyable
    return true;
  }

  // How many times store() has completed (any thread).
  std::uint64_t version() const noexcept { return sequence_.load(std::memory_order_acquire) / 2; }

 private:
  static constexpr std::size_t word_count = (sizeof(T) + sizeof(std::uint64_t) - 1) / sizeof(std::uint64_t);

  void write_words(const T& value, std::memory_order order) noexcept {
    std::array<std::uint64_t, word_count> words{};
    std::memcpy(words.data(), &value, sizeof(T));
    for (std::size_t i = 0; i < word_count; ++i) words_[i].store(words[i], order);
  }

  alignas(64) std::atomic<std::uint64_t> sequence_{0};
  std::array<std::atomic<std::uint64_t>, word_count> words_;
};

}  // namespace palpate
