// Debouncing as a property: over seeded random lines (bursts of bounces, glitches, clean holds),
// the settled value only ever takes a value the line held untouched for the whole window before,
// and every hold of at least the window is taken by its end.

#include "avar/inputs/debouncer.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace avar::inputs {
namespace {

struct DebounceChange {
  std::int64_t t;
  bool level;
};

/// A line that bounces: holds of random length, some far shorter than the window.
std::vector<DebounceChange> debounce_random_line(std::mt19937& rng, std::int64_t window) {
  std::vector<DebounceChange> line;
  std::uniform_int_distribution<std::int64_t> short_gap(1, window / 4), long_gap(window, 6 * window);
  std::bernoulli_distribution bursty(0.6);
  std::int64_t t = 0;
  bool level = false;
  for (int k = 0; k < 400; ++k) {
    t += bursty(rng) ? short_gap(rng) : long_gap(rng);
    level = !level;
    line.push_back({t, level});
  }
  return line;
}

TEST(Debouncer, SettlesOnlyOnValuesHeldForTheWholeWindowAndOnEveryLongHold) {
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    const std::int64_t window = 10'000'000;  // 10 ms
    const std::vector<DebounceChange> line = debounce_random_line(rng, window);
    Debouncer d(window, false);
    bool level = false;
    std::int64_t last_change = 0;
    std::size_t settled_changes = 0;
    for (std::size_t i = 0; i <= line.size(); ++i) {
      const std::int64_t next = i < line.size() ? line[i].t : line.back().t + 10 * window;
      // The owner wakes at the deadline if it comes before the next change.
      if (d.pending() && d.deadline_ns() <= next) {
        ASSERT_TRUE(d.due(d.deadline_ns()));
        const std::int64_t at = d.deadline_ns();
        if (d.settle(level)) {
          ++settled_changes;
          EXPECT_GE(at - last_change, window) << "settled on a value held only " << (at - last_change) << " ns";
        }
        EXPECT_EQ(d.value(), level);  // a hold of a whole window is always taken
      }
      if (i == line.size()) break;
      // A hold that lasted the window must have been settled before the line moves again.
      if (next - last_change >= window && i > 0) {
        EXPECT_EQ(d.value(), level) << "change " << i;
      }
      level = line[i].level;
      last_change = line[i].t;
      d.disturbed(line[i].t);
    }
    EXPECT_EQ(d.value(), line.back().level);
    EXPECT_LE(settled_changes, line.size());
  }
}

TEST(Debouncer, AGlitchShorterThanTheWindowNeverShows) {
  Debouncer d(5'000'000, false);
  d.disturbed(0);          // up
  d.disturbed(1'000'000);  // and down again 1 ms later
  EXPECT_FALSE(d.due(5'999'999));
  ASSERT_TRUE(d.due(6'000'000));
  EXPECT_FALSE(d.settle(false));  // the window ended on the settled value: a glitch
  EXPECT_FALSE(d.value());
  EXPECT_FALSE(d.pending());
}

TEST(Debouncer, AZeroWindowTakesEveryReading) {
  Debouncer d(0, true);
  d.disturbed(42);
  ASSERT_TRUE(d.due(42));
  EXPECT_TRUE(d.settle(false));
  EXPECT_FALSE(d.value());
}

}  // namespace
}  // namespace avar::inputs
