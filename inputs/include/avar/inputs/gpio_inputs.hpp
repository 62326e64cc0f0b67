#pragma once
// Digital inputs on GPIO lines (e-stop, limit switches, show start buttons), watched by one
// thread per chip: each waits for the chip's edge events (and re-reads every line every
// kRecheck, so a lost edge or a chip without events is still seen), debounces every line
// (Debouncer), and acts on each settled change by the input's role:
//
//   estop    the e-stop flag (estop()) goes true and stays true until reset_estop(). It trips on
//            the first reading of the active level, before the debounce window (a glitch stops
//            the figure, never the other way round), and also when the chip fails (a read or a
//            wait that errors).
//   control  posts the value (0 or 1, unipolar) to the ControlSink under the input's name.
//   start    counts presses (settled changes to active): start_presses().
//
// Values are logical: an input with active_low is active (1) while its line is low.
// Lifetime: lines are requested by the constructor and given back by the destructor; start()
// reads every line once on the calling thread (so an e-stop held at start is set before it
// returns, and each control's first value is posted), then starts the threads.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "avar/inputs/debouncer.hpp"
#include "avar/firmware_iface/gpio_chip.hpp"
#include "avar/inputs/input_source.hpp"

namespace avar::inputs {

enum class GpioInputRole { estop, control, start };

struct GpioInputConfig {
  std::string name;  ///< the control's name for the sink, and for messages
  std::shared_ptr<firmware_iface::GpioChip> chip;
  firmware_iface::GpioInputRequest request;  ///< line, active_low, bias; edge_events is forced on
  std::chrono::nanoseconds debounce = std::chrono::milliseconds(10);
  GpioInputRole role = GpioInputRole::control;
};

class GpioInputs final : public InputSource {
 public:
  /// How often each thread re-reads its lines besides waiting for their edges.
  static constexpr std::chrono::milliseconds kRecheck{20};

  /// Requests every input line. Throws std::invalid_argument for no inputs, a missing chip or a
  /// negative debounce, std::runtime_error naming the chip and line when a request fails.
  explicit GpioInputs(std::vector<GpioInputConfig> inputs);
  ~GpioInputs() override;
  GpioInputs(const GpioInputs&) = delete;
  GpioInputs& operator=(const GpioInputs&) = delete;

  /// Reads every line, then starts the threads; control inputs post into `sink` (borrowed).
  /// Called once. Throws std::runtime_error naming the chip and line when a first read fails.
  void start(ControlSink& sink) override;
  /// The same without a sink: control inputs are only kept (value()).
  void start();
  void stop() noexcept override;
  /// "GPIO inputs estop (GPIO chip 'gpiochip0' (...) line 4, e-stop), door (... line 5, control)".
  std::string describe() const override;
  /// messages: settled changes; ignored: windows that ended on the settled value (bounces,
  /// glitches). Any thread.
  InputCounters counters() const noexcept override;

  /// The e-stop, for control::RunOptions::estop: true from the first active reading of any estop
  /// input (or a failing chip that has one) until reset_estop(). Any thread.
  const std::atomic<bool>& estop() const noexcept { return estop_; }
  /// Clears the e-stop when no estop input is active any more (settled, nor read now); returns
  /// whether it did. Any thread.
  bool reset_estop() noexcept;
  /// Presses of start inputs since start(). Any thread.
  std::uint64_t start_presses() const noexcept { return start_presses_.load(std::memory_order_relaxed); }
  /// Input i's settled value (in the constructor's order). Any thread.
  bool value(std::size_t input) const noexcept { return inputs_[input]->settled.load(std::memory_order_relaxed); }
  std::size_t size() const noexcept { return inputs_.size(); }
  const std::string& name(std::size_t input) const noexcept { return inputs_[input]->config.name; }

 private:
  struct Input {
    GpioInputConfig config;
    Debouncer debouncer{0, false};  ///< the chip's thread only, after start()
    std::atomic<bool> settled{false};
  };

  /// The inputs on one chip, and the thread that watches them.
  struct Watch {
    firmware_iface::GpioChip* chip = nullptr;
    std::vector<Input*> inputs;
    std::thread thread;
  };

  void watch(Watch& w) noexcept;
  /// Reads an input's line: false (and the e-stop tripped for an estop input) when it fails.
  bool read(Input& in, bool& value) noexcept;
  void report(Input& in, bool value, std::int64_t now_ns) noexcept;
  /// A failure of a chip that carries an e-stop trips it.
  void chip_failed(const Watch& w) noexcept;

  std::vector<std::unique_ptr<Input>> inputs_;
  std::vector<std::unique_ptr<Watch>> watches_;
  ControlSink* sink_ = nullptr;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> estop_{false};
  std::atomic<std::uint64_t> start_presses_{0};
  std::atomic<std::uint64_t> messages_{0};
  std::atomic<std::uint64_t> ignored_{0};
  bool started_ = false;
};

}  // namespace avar::inputs
