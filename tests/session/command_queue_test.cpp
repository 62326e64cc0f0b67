#include <gtest/gtest.h>

#include <set>
#include <thread>
#include <vector>

#include "avar/session/command_queue.hpp"

namespace avar::session {
namespace {

TEST(CommandQueue, RefusesWhenFullAndKeepsOrder) {
  CommandQueue q(4);
  EXPECT_EQ(q.capacity(), 4u);
  for (std::uint32_t i = 0; i < 4; ++i) EXPECT_TRUE(q.push({CommandKind::hold, i, 1.0 * i}));
  EXPECT_FALSE(q.push({CommandKind::stop, 0, 0}));
  Command c;
  for (std::uint32_t i = 0; i < 4; ++i) {
    ASSERT_TRUE(q.pop(c));
    EXPECT_EQ(c.channel, i);
  }
  EXPECT_FALSE(q.pop(c));
  EXPECT_TRUE(q.push({CommandKind::stop, 0, 0}));
}

TEST(CommandQueue, ManyProducersOneConsumerLoseNothingTheyWerePromised) {
  CommandQueue q(64);
  constexpr std::uint32_t kPerThread = 20000;
  std::vector<std::thread> producers;
  std::atomic<std::uint64_t> accepted{0};
  for (std::uint32_t t = 0; t < 4; ++t)
    producers.emplace_back([&, t] {
      for (std::uint32_t i = 0; i < kPerThread; ++i)
        while (!q.push({CommandKind::hold, t, static_cast<double>(i)})) std::this_thread::yield();
      accepted.fetch_add(kPerThread);
    });
  std::vector<double> last(4, -1);
  std::uint64_t popped = 0;
  Command c;
  while (popped < 4u * kPerThread) {
    if (!q.pop(c)) {
      std::this_thread::yield();
      continue;
    }
    // Each producer's commands arrive in its order.
    ASSERT_GT(c.value, last[c.channel]);
    last[c.channel] = c.value;
    ++popped;
  }
  for (std::thread& p : producers) p.join();
  EXPECT_EQ(accepted.load(), popped);
  EXPECT_FALSE(q.pop(c));
}

}  // namespace
}  // namespace avar::session
