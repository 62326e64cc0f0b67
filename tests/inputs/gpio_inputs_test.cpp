// Digital inputs watched on a simulated GPIO chip by their own threads: an e-stop trips on its
// first active reading and stays latched; controls reach the sink once per settled change,
// active-low inverted, bounces and glitches filtered; start buttons count presses.

#include "avar/inputs/gpio_inputs.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "avar/sim/sim_gpio_chip.hpp"

namespace avar::inputs {
namespace {

using namespace std::chrono_literals;

/// Keeps every post, for the test thread to read.
class GpioRecordingSink final : public ControlSink {
 public:
  struct Post {
    std::string control;
    double value;
    bool bipolar;
  };
  void post(std::string_view control, double value, bool bipolar, std::int64_t) noexcept override {
    const std::lock_guard lock(mutex_);
    posts_.push_back({std::string(control), value, bipolar});
  }
  std::vector<Post> posts() const {
    const std::lock_guard lock(mutex_);
    return posts_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<Post> posts_;
};

/// Polls `done` until it holds or 5 s pass (a loaded machine may keep the input thread waiting).
template <class Done>
bool gpio_eventually(Done done) {
  const auto until = std::chrono::steady_clock::now() + 5s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

GpioInputConfig gpio_input(std::string name, std::shared_ptr<sim::SimGpioChip> chip, unsigned line, bool active_low,
                           GpioInputRole role, std::chrono::nanoseconds debounce) {
  GpioInputConfig c;
  c.name = std::move(name);
  c.chip = std::move(chip);
  c.request = {line, active_low, firmware_iface::GpioBias::pull_up, true};
  c.debounce = debounce;
  c.role = role;
  return c;
}

TEST(GpioInputs, AnEstopTripsAtOnceAndStaysLatchedUntilReleasedAndReset) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  // A normally-closed e-stop to ground on a pulled-up line: pressing it opens the contact and
  // the line goes high; a cut wire does the same.
  GpioInputs inputs({gpio_input("estop", chip, 4, false, GpioInputRole::estop, 200ms)});
  chip->set_level(4, false);
  inputs.start();
  EXPECT_FALSE(inputs.estop().load());
  const auto pressed_at = std::chrono::steady_clock::now();
  chip->set_level(4, true);
  ASSERT_TRUE(gpio_eventually([&] { return inputs.estop().load(); }));
  // Before the 200 ms window could have ended: the e-stop does not wait for the debounce.
  EXPECT_LT(std::chrono::steady_clock::now() - pressed_at, 200ms);
  EXPECT_FALSE(inputs.reset_estop());  // still pressed
  ASSERT_TRUE(gpio_eventually([&] { return inputs.value(0); }));
  chip->set_level(4, false);           // released
  EXPECT_TRUE(inputs.estop().load());  // latched
  ASSERT_TRUE(gpio_eventually([&] { return !inputs.value(0); }));
  EXPECT_TRUE(inputs.reset_estop());
  EXPECT_FALSE(inputs.estop().load());
}

TEST(GpioInputs, AnEstopHeldAtStartIsSetBeforeStartReturns) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  GpioInputs inputs({gpio_input("estop", chip, 4, true, GpioInputRole::estop, 10ms)});
  chip->set_level(4, false);  // active-low, pressed
  inputs.start();
  EXPECT_TRUE(inputs.estop().load());
}

TEST(GpioInputs, ControlsPostOncePerSettledChangeActiveLowInverted) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  GpioRecordingSink sink;
  GpioInputs inputs({gpio_input("door", chip, 6, true, GpioInputRole::control, 30ms)});
  inputs.start(sink);
  ASSERT_EQ(sink.posts().size(), 1u);  // the first value, at start: pulled up, active-low: 0
  EXPECT_EQ(sink.posts()[0].control, "door");
  EXPECT_EQ(sink.posts()[0].value, 0.0);
  EXPECT_FALSE(sink.posts()[0].bipolar);

  // A switch closing with a burst of bounces, then holding: one change to 1.
  for (int i = 0; i < 9; ++i) chip->set_level(6, i % 2 == 1);
  chip->set_level(6, false);
  ASSERT_TRUE(gpio_eventually([&] { return sink.posts().size() == 2; }));
  EXPECT_EQ(sink.posts()[1].value, 1.0);
  std::this_thread::sleep_for(80ms);  // more than the window: nothing else comes
  EXPECT_EQ(sink.posts().size(), 2u);
  EXPECT_TRUE(inputs.value(0));
  EXPECT_EQ(inputs.counters().messages, 1u);
}

TEST(GpioInputs, AGlitchShorterThanTheDebounceIsIgnored) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  GpioRecordingSink sink;
  GpioInputs inputs({gpio_input("limit", chip, 7, false, GpioInputRole::control, 300ms)});
  chip->set_level(7, false);
  inputs.start(sink);
  chip->set_level(7, true);
  chip->set_level(7, false);  // back within microseconds
  ASSERT_TRUE(gpio_eventually([&] { return inputs.counters().ignored >= 1; }));
  EXPECT_EQ(sink.posts().size(), 1u);  // the first value only
  EXPECT_FALSE(inputs.value(0));
}

TEST(GpioInputs, StartButtonsCountPresses) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  GpioInputs inputs({gpio_input("start", chip, 9, true, GpioInputRole::start, 5ms),
                     gpio_input("estop", chip, 4, true, GpioInputRole::estop, 5ms)});
  inputs.start();
  for (int press = 1; press <= 3; ++press) {
    chip->set_level(9, false);
    ASSERT_TRUE(gpio_eventually([&] { return inputs.start_presses() == static_cast<std::uint64_t>(press); }));
    chip->set_level(9, true);
    ASSERT_TRUE(gpio_eventually([&] { return !inputs.value(0); }));
  }
  EXPECT_FALSE(inputs.estop().load());  // another line, untouched
  EXPECT_EQ(
      inputs.describe(),
      "GPIO inputs start (simulated GPIO chip 'sim' line 9, start button), estop (simulated GPIO chip 'sim' line 4, e-stop)");
}

TEST(GpioInputs, LinesAreRequestedForTheirLifetimeAndBusyLinesAreNamed) {
  auto chip = std::make_shared<sim::SimGpioChip>();
  {
    GpioInputs inputs({gpio_input("a", chip, 1, false, GpioInputRole::control, 1ms)});
    EXPECT_TRUE(chip->is_requested(1));
    try {
      GpioInputs again({gpio_input("b", chip, 2, false, GpioInputRole::control, 1ms),
                        gpio_input("c", chip, 1, false, GpioInputRole::control, 1ms)});
      FAIL() << "line 1 is in use";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "simulated GPIO chip 'sim': cannot request line 1 as an input: it is in use (requested twice)");
    }
    EXPECT_FALSE(chip->is_requested(2));  // the failed set gave back what it had taken
  }
  EXPECT_FALSE(chip->is_requested(1));
}

}  // namespace
}  // namespace avar::inputs
