#include "avar/core/atomic_counters.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <thread>

namespace avar {
namespace {

struct ThreeCounters {
  std::uint64_t sent = 0;
  std::uint64_t received = 0;
  std::uint64_t lost = 0;
};

TEST(AtomicCounters, AddsToTheNamedCounterOnly) {
  AtomicCounters<ThreeCounters> c;
  c.add(&ThreeCounters::received);
  c.add(&ThreeCounters::received, 4);
  c.add(&ThreeCounters::lost, 2);
  const ThreeCounters k = c.snapshot();
  EXPECT_EQ(k.sent, 0u);
  EXPECT_EQ(k.received, 5u);
  EXPECT_EQ(k.lost, 2u);
}

TEST(AtomicCounters, AddsABatchCounterByCounter) {
  AtomicCounters<ThreeCounters> c;
  c.add(&ThreeCounters::sent, 7);
  c.add(ThreeCounters{1, 2, 3});
  const ThreeCounters k = c.snapshot();
  EXPECT_EQ(k.sent, 8u);
  EXPECT_EQ(k.received, 2u);
  EXPECT_EQ(k.lost, 3u);
}

TEST(AtomicCounters, EveryAddFromAnotherThreadIsCounted) {
  AtomicCounters<ThreeCounters> c;
  std::thread writer([&] {
    for (int i = 0; i < 10000; ++i) c.add(&ThreeCounters::sent);
  });
  std::uint64_t seen = 0;
  while (seen < 10000) {
    const std::uint64_t now = c.snapshot().sent;
    EXPECT_GE(now, seen);  // never goes back
    seen = now;
  }
  writer.join();
  EXPECT_EQ(c.snapshot().sent, 10000u);
}

}  // namespace
}  // namespace avar
