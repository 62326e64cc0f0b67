// GPIO figures end to end through the library: a rig with a gpio link on a simulated chip plays
// a show whose step keys toggle a relay, read off the chip's output line tick by tick; an e-stop
// pressed on the simulated chip mid-show latches the e-stop fault through the input thread and
// run_loop, and every actuator ends in its fail-safe state.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "avar/assembly/digital_inputs.hpp"
#include "avar/assembly/figure_links.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/config/show_check.hpp"
#include "avar/config/show_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/control/runner.hpp"
#include "avar/firmware_iface/libgpiod_chip.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "../support/temp_file.hpp"

namespace avar {
namespace {

constexpr unsigned kFogLine = 17, kStrobeLine = 27, kEstopLine = 4;

/// Whether show time t is at or past a key at `key` s: a tick whose show time rounds to just
/// below the key (3.0999999999999996 for 3.1) is the key's tick (Curve::kKeySnap).
bool at_or_past(double t, double key) { return t >= key - playback::Curve::kKeySnap; }

/// The example's fog and strobe as the show keys them (step keys), at show time t.
bool gpio_fog_keyed(double t) { return at_or_past(t, 0.5) && !at_or_past(t, 5.0); }
bool gpio_strobe_keyed(double t) {
  const double on[][2] = {{3.0, 3.1}, {3.3, 3.4}, {3.6, 3.7}, {6.2, 6.3}};
  for (const auto& span : on)
    if (at_or_past(t, span[0]) && !at_or_past(t, span[1])) return true;
  return false;
}

/// Runs `figure` on the stepped clock, optionally watching an e-stop flag.
control::RunResult gpio_run(control::Controller& controller, assembly::FigureLinks& figure, control::TickObserver& observer,
                            double rate_hz, const std::atomic<bool>* estop = nullptr) {
  control::RunOptions run{rate_hz, control::ClockMode::stepped, {}};
  run.plant = &figure;
  run.estop_input = estop;
  const std::atomic<int> no_interrupts{0};
  return control::run_loop(controller, run, observer, no_interrupts);
}

control::ControllerOptions gpio_controller_options(const rig::Rig& rig, assembly::FigureLinks& figure) {
  control::ControllerOptions o;
  o.tick_period_s = 1.0 / rig.rate_hz;
  o.stage_clock = nullptr;
  o.positions = &figure;
  return o;
}

/// Reads the simulated chip's output lines after every tick.
class GpioLineWatch final : public control::TickObserver {
 public:
  explicit GpioLineWatch(sim::SimGpioChip& chip) : chip_(chip) {}
  void after_tick(std::uint64_t, double now, double, double, control::Controller& c) override {
    phases.push_back(c.phase());
    show_times.push_back(c.phase() == control::Phase::running ? now - c.show_start_time() : -1);
    fog.push_back(chip_.level(kFogLine));
    strobe_low.push_back(!chip_.level(kStrobeLine));
    commanded_fog.push_back(c.commanded()[1]);
  }
  std::vector<control::Phase> phases;
  std::vector<double> show_times;
  std::vector<bool> fog, strobe_low;
  std::vector<double> commanded_fog;

 private:
  sim::SimGpioChip& chip_;
};

TEST(GpioFigure, StepKeysToggleTheRelayLineOnTheirTicks) {
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/haunt-prop.yaml");
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/haunt-prop.yaml");
  const config::ShowCheck check = config::check_show_against_rig(show, rig);
  ASSERT_TRUE(check.ok());
  EXPECT_TRUE(check.warnings.empty()) << check.warnings.front().to_string();
  auto chips = std::make_shared<assembly::GpioChips>();
  assembly::LinkSelection selection;
  selection.gpio_chips = chips;
  assembly::FigureLinks figure(rig, selection);
  EXPECT_TRUE(figure.all_simulated());
  EXPECT_EQ(figure.describe(1), "GPIO link 'pi' on simulated GPIO chip 'sim'");
  for (firmware_iface::ActuatorLink* link : figure.links()) ASSERT_EQ(link->start(), Status::ok);
  sim::SimGpioChip& chip = chips->simulated();
  EXPECT_TRUE(chip.is_output(kFogLine));
  EXPECT_TRUE(chip.level(kStrobeLine));  // requested at rest: off, active-low high

  control::Controller controller(rig, show, figure.links(), gpio_controller_options(rig, figure));
  controller.begin(0.0, rig.rest_frame());
  GpioLineWatch watch(chip);
  const control::RunResult result = gpio_run(controller, figure, watch, rig.rate_hz);
  EXPECT_EQ(controller.latched_fault().cause, control::FaultCause::none);
  ASSERT_GT(result.ticks, 400u);

  std::size_t running = 0;
  for (std::size_t k = 0; k < watch.phases.size(); ++k) {
    const double v = watch.commanded_fog[k];
    ASSERT_TRUE(v == 0.0 || v == 1.0) << v;  // never anything between
    if (watch.phases[k] != control::Phase::running) continue;
    ++running;
    const double t = watch.show_times[k];
    EXPECT_EQ(watch.fog[k], gpio_fog_keyed(t)) << "show time " << t;
    EXPECT_EQ(watch.strobe_low[k], gpio_strobe_keyed(t)) << "show time " << t;
  }
  EXPECT_GE(running, 399u);  // 8 s at 50 Hz
  // Both lines changed only on their keys: fog on, off; strobe four flashes.
  EXPECT_EQ(chip.output_changes(kFogLine), 2u);
  EXPECT_EQ(chip.output_changes(kStrobeLine), 8u);
  EXPECT_FALSE(chip.level(kFogLine));
  // The simulated chip's lines are the relay's ground truth: the tracking check sees them.
  std::vector<double> measured(rig.channels.size(), -1);
  std::unique_ptr<bool[]> known(new bool[rig.channels.size()]());
  figure.measure(measured, std::span<bool>(known.get(), rig.channels.size()));
  EXPECT_TRUE(known[1]);
  EXPECT_EQ(measured[1], 0.0);
}

/// Presses the e-stop on the simulated chip after tick `at`, and holds the loop until the input
/// thread has seen it (so the run is the same on every machine).
class GpioEstopPress final : public control::TickObserver {
 public:
  GpioEstopPress(sim::SimGpioChip& chip, const std::atomic<bool>& estop, std::uint64_t at)
      : chip_(chip), estop_(estop), at_(at) {}
  void after_tick(std::uint64_t tick, double now, double, double, control::Controller& c) override {
    if (tick == at_) {
      lid_at_press = c.commanded()[0];
      fog_at_press = chip_.level(kFogLine);
      pressed_at_s = now;
      chip_.set_level(kEstopLine, false);  // a button to ground, active-low
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
      while (!estop_.load() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    if (tick == at_ + 1) fog_after_press = chip_.level(kFogLine);
  }
  double lid_at_press = -1, pressed_at_s = -1;
  bool fog_at_press = false, fog_after_press = true;

 private:
  sim::SimGpioChip& chip_;
  const std::atomic<bool>& estop_;
  std::uint64_t at_;
};

TEST(GpioFigure, AnEstopOnTheSimulatedChipMidShowEndsInTheFailSafeState) {
  const rig::Rig rig = config::load_rig_file(AVAR_SOURCE_DIR "/examples/rigs/haunt-prop.yaml");
  const playback::Show show = config::load_show_file(AVAR_SOURCE_DIR "/examples/shows/haunt-prop.yaml");
  auto chips = std::make_shared<assembly::GpioChips>();
  assembly::LinkSelection selection;
  selection.gpio_chips = chips;
  assembly::FigureLinks figure(rig, selection);
  for (firmware_iface::ActuatorLink* link : figure.links()) ASSERT_EQ(link->start(), Status::ok);
  std::unique_ptr<inputs::GpioInputs> inputs = assembly::open_digital_inputs(rig, *chips);
  ASSERT_TRUE(inputs);
  inputs->start();
  ASSERT_FALSE(inputs->estop().load());  // pulled up, not pressed

  control::Controller controller(rig, show, figure.links(), gpio_controller_options(rig, figure));
  controller.begin(0.0, rig.rest_frame());
  sim::SimGpioChip& chip = chips->simulated();
  // Mid-show (show time ~3.0 s after a soft start of a fraction of a second), fog on, lid up,
  // strobe flashing.
  GpioEstopPress press(chip, inputs->estop(), 180);
  const control::RunResult result = gpio_run(controller, figure, press, rig.rate_hz, &inputs->estop());
  inputs->stop();

  const control::Fault& fault = controller.latched_fault();
  EXPECT_EQ(fault.cause, control::FaultCause::estop);
  EXPECT_EQ(fault.from, control::Phase::running);
  EXPECT_NEAR(fault.time_s, press.pressed_at_s + 1.0 / rig.rate_hz, 1e-9);  // the very next tick
  EXPECT_FALSE(controller.active());
  EXPECT_LT(result.ticks, 400u);  // the show's 8 s were cut short
  ASSERT_TRUE(press.fog_at_press);
  EXPECT_GT(press.lid_at_press, 20.0);

  // Fail-safe: the fog relay (rest) off on the fault's tick, the strobe (release) let go: off,
  // active-low high; the lid (rest) eased down to rest.
  EXPECT_FALSE(press.fog_after_press);
  EXPECT_FALSE(chip.level(kFogLine));
  EXPECT_TRUE(chip.level(kStrobeLine));
  std::vector<double> measured(rig.channels.size(), -1);
  std::unique_ptr<bool[]> known(new bool[rig.channels.size()]());
  figure.measure(measured, std::span<bool>(known.get(), rig.channels.size()));
  ASSERT_TRUE(known[0]);
  EXPECT_NEAR(measured[0], 0.0, 0.5);  // the simulated servo's true angle, deg
  EXPECT_DOUBLE_EQ(controller.commanded()[0], 0.0);
  EXPECT_TRUE(inputs->estop().load());  // latched until reset, the button still held
  EXPECT_FALSE(inputs->reset_estop());
}

TEST(GpioFigure, AChipThatIsNotThereIsNamedAtTheLink) {
  if (!firmware_iface::gpio_chip_names().empty()) GTEST_SKIP() << "this machine has GPIO chips";
  const std::string path = testing::write_temp_file("gpio_real.yaml", R"(name: real
links:
  pi: {port: gpiochip0, gpio: {}}
channels:
  fog: {kind: digital}
actuators:
  - {channel: fog, link: pi, line: 17}
)");
  const rig::Rig rig = config::load_rig_file(path);
  try {
    assembly::FigureLinks figure(rig, {});
    FAIL() << "opened a chip that is not there";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ":3:7: link 'pi': no GPIO chip 'gpiochip0' (this machine has none: /dev/gpiochip* absent)");
  }
  // --sim simulates it.
  assembly::LinkSelection selection;
  selection.simulate_all = true;
  assembly::FigureLinks figure(rig, selection);
  EXPECT_TRUE(figure.all_simulated());
  EXPECT_EQ(figure.describe(0), "GPIO link 'pi' on simulated GPIO chip 'gpiochip0'");
}

}  // namespace
}  // namespace avar
