#pragma once
// The atomic mirror of a plain struct of event counters (a link's, a frame transport's, an input
// device's, a timecode source's), kept by one thread and read from any: one relaxed atomic per
// counter. Each value read is exact; a snapshot is not one instant across the counters.
//
// `Counters`: an aggregate whose members are all std::uint64_t counters (no other member, no
// padding), such as struct { std::uint64_t replies = 0; std::uint64_t timeouts = 0; }.
// Real-time safe: no allocation, no lock, no exception.

#include <array>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <type_traits>

namespace avar {

template <class Counters>
class AtomicCounters {
  static_assert(std::is_trivially_copyable_v<Counters> && std::is_standard_layout_v<Counters> &&
                    std::has_unique_object_representations_v<Counters> && sizeof(Counters) % sizeof(std::uint64_t) == 0,
                "Counters must hold std::uint64_t members only");

 public:
  /// A counter of Counters, as &Counters::name.
  using Counter = std::uint64_t Counters::*;

  /// Adds n to one counter (`counters.add(&LinkCounters::timeouts)`). The writer's thread.
  void add(Counter counter, std::uint64_t n = 1) noexcept { values_[index_of(counter)].fetch_add(n, std::memory_order_relaxed); }
  /// Adds every counter of `batch`. The writer's thread.
  void add(const Counters& batch) noexcept {
    const auto v = std::bit_cast<Values>(batch);
    for (std::size_t i = 0; i < kCount; ++i)
      if (v[i] != 0) values_[i].fetch_add(v[i], std::memory_order_relaxed);
  }
  /// The counters as they stand. Any thread.
  Counters snapshot() const noexcept {
    Values v{};
    for (std::size_t i = 0; i < kCount; ++i) v[i] = values_[i].load(std::memory_order_relaxed);
    return std::bit_cast<Counters>(v);
  }

 private:
  static constexpr std::size_t kCount = sizeof(Counters) / sizeof(std::uint64_t);
  using Values = std::array<std::uint64_t, kCount>;

  /// A Counters whose every member holds its own place among the members.
  static constexpr Counters places() noexcept {
    Values v{};
    for (std::size_t i = 0; i < kCount; ++i) v[i] = i;
    return std::bit_cast<Counters>(v);
  }
  static constexpr Counters kPlaces = places();
  /// The counter's place (a constant when `counter` is one).
  static constexpr std::size_t index_of(Counter counter) noexcept { return static_cast<std::size_t>(kPlaces.*counter); }

  std::array<std::atomic<std::uint64_t>, kCount> values_{};
};

}  // namespace avar
