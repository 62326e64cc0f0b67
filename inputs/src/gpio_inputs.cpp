#include "avar/inputs/gpio_inputs.hpp"

#include <ctime>

#include <algorithm>
#include <stdexcept>

#include "avar/core/monotonic_clock.hpp"
#include "avar/inputs/atomic_input_counters.hpp"

namespace avar::inputs {
namespace {

/// Where inputs go when the owner gave no sink.
class NoSink final : public ControlSink {
 public:
  void post(std::string_view, double, bool, std::int64_t) noexcept override {}
};

NoSink g_no_sink;

const char* role_text(GpioInputRole r) {
  switch (r) {
    case GpioInputRole::estop: return "e-stop";
    case GpioInputRole::control: return "control";
    case GpioInputRole::start: return "start button";
  }
  return "unknown";
}

}  // namespace

GpioInputs::GpioInputs(std::vector<GpioInputConfig> inputs) {
  if (inputs.empty()) throw std::invalid_argument("GPIO inputs: none configured");
  for (GpioInputConfig& c : inputs) {
    if (!c.chip) throw std::invalid_argument("GPIO input '" + c.name + "' has no chip");
    if (c.debounce.count() < 0) throw std::invalid_argument("GPIO input '" + c.name + "' has a negative debounce");
    c.request.edge_events = true;
    auto in = std::make_unique<Input>();
    in->config = std::move(c);
    in->debouncer = Debouncer(in->config.debounce.count(), false);
    inputs_.push_back(std::move(in));
  }
  std::size_t requested = 0;
  try {
    for (const auto& in : inputs_) {
      in->config.chip->request_input(in->config.request);
      ++requested;
    }
  } catch (...) {
    for (std::size_t i = 0; i < requested; ++i) inputs_[i]->config.chip->release(inputs_[i]->config.request.line);
    throw;
  }
  for (const auto& in : inputs_) {
    firmware_iface::GpioChip* chip = in->config.chip.get();
    auto w = std::find_if(watches_.begin(), watches_.end(), [&](const auto& x) { return x->chip == chip; });
    if (w == watches_.end()) {
      watches_.push_back(std::make_unique<Watch>());
      watches_.back()->chip = chip;
      w = watches_.end() - 1;
    }
    (*w)->inputs.push_back(in.get());
  }
}

GpioInputs::~GpioInputs() {
  stop();
  for (const auto& in : inputs_) in->config.chip->release(in->config.request.line);
}

void GpioInputs::start() { start(g_no_sink); }

void GpioInputs::start(ControlSink& sink) {
  if (started_) return;
  sink_ = &sink;
  const std::int64_t now = monotonic_ns();
  for (const auto& in : inputs_) {
    bool v = false;
    if (!read(*in, v))
      throw std::runtime_error("GPIO input '" + in->config.name + "': cannot read line " +
                               std::to_string(in->config.request.line) + " of " + in->config.chip->describe());
    in->debouncer = Debouncer(in->config.debounce.count(), v);
    in->settled.store(v, std::memory_order_relaxed);
    if (in->config.role == GpioInputRole::control) sink_->post(in->config.name, v ? 1.0 : 0.0, false, now);
  }
  started_ = true;
  stopping_.store(false, std::memory_order_relaxed);
  for (const auto& w : watches_) w->thread = std::thread([this, w = w.get()] { watch(*w); });
}

void GpioInputs::stop() noexcept {
  stopping_.store(true, std::memory_order_relaxed);
  for (const auto& w : watches_)
    if (w->thread.joinable()) w->thread.join();
}

std::string GpioInputs::describe() const {
  std::string text = "GPIO inputs ";
  for (std::size_t i = 0; i < inputs_.size(); ++i) {
    const GpioInputConfig& c = inputs_[i]->config;
    text += (i ? ", " : "") + c.name + " (" + c.chip->describe() + " line " + std::to_string(c.request.line) + ", " +
            role_text(c.role) + ")";
  }
  return text;
}

InputCounters GpioInputs::counters() const noexcept {
  return {messages_.load(std::memory_order_relaxed), ignored_.load(std::memory_order_relaxed)};
}

bool GpioInputs::reset_estop() noexcept {
  for (const auto& in : inputs_) {
    if (in->config.role != GpioInputRole::estop) continue;
    // Settled inactive is not enough: a press may be inside its window. Ask the line too.
    bool active = true;
    if (in->settled.load(std::memory_order_relaxed) || in->config.chip->get(in->config.request.line, active) != Status::ok ||
        active)
      return false;
  }
  estop_.store(false, std::memory_order_relaxed);
  return true;
}

bool GpioInputs::read(Input& in, bool& value) noexcept {
  if (in.config.chip->get(in.config.request.line, value) != Status::ok) {
    if (in.config.role == GpioInputRole::estop) estop_.store(true, std::memory_order_relaxed);
    return false;
  }
  if (in.config.role == GpioInputRole::estop && value) estop_.store(true, std::memory_order_relaxed);
  return true;
}

void GpioInputs::report(Input& in, bool value, std::int64_t now_ns) noexcept {
  in.settled.store(value, std::memory_order_relaxed);
  messages_.fetch_add(1, std::memory_order_relaxed);
  switch (in.config.role) {
    case GpioInputRole::estop:
      if (value) estop_.store(true, std::memory_order_relaxed);
      break;
    case GpioInputRole::control: sink_->post(in.config.name, value ? 1.0 : 0.0, false, now_ns); break;
    case GpioInputRole::start:
      if (value) start_presses_.fetch_add(1, std::memory_order_relaxed);
      break;
  }
}

void GpioInputs::chip_failed(const Watch& w) noexcept {
  for (const Input* in : w.inputs)
    if (in->config.role == GpioInputRole::estop) estop_.store(true, std::memory_order_relaxed);
}

void GpioInputs::watch(Watch& w) noexcept {
  firmware_iface::GpioEdge edges[32];
  std::int64_t next_recheck = 0;
  while (!stopping_.load(std::memory_order_relaxed)) {
    std::int64_t now = monotonic_ns();
    // Windows that are over: the line stayed put, take its value.
    for (Input* in : w.inputs) {
      if (!in->debouncer.due(now)) continue;
      bool v = false;
      if (!read(*in, v)) {
        chip_failed(w);
        in->debouncer.disturbed(now);
        continue;
      }
      if (in->debouncer.settle(v)) report(*in, v, now);
      else ignored_.fetch_add(1, std::memory_order_relaxed);
    }
    // Now and then, every line that is not settling: a lost edge still shows.
    if (now >= next_recheck) {
      next_recheck = now + std::chrono::nanoseconds(kRecheck).count();
      for (Input* in : w.inputs) {
        bool v = false;
        if (!read(*in, v)) chip_failed(w);
        else if (!in->debouncer.pending() && v != in->debouncer.value()) in->debouncer.disturbed(now);
      }
    }
    std::int64_t wake = next_recheck;
    for (const Input* in : w.inputs)
      if (in->debouncer.pending()) wake = std::min(wake, in->debouncer.deadline_ns());
    std::size_t n = 0;
    if (w.chip->wait_edges(std::chrono::nanoseconds(std::max<std::int64_t>(wake - now, 0)), edges, n) != Status::ok) {
      chip_failed(w);
      // Not a busy loop on a chip that keeps failing.
      const timespec pause{0, 10'000'000};
      nanosleep(&pause, nullptr);
      continue;
    }
    now = monotonic_ns();
    for (std::size_t e = 0; e < n; ++e)
      for (Input* in : w.inputs) {
        if (in->config.request.line != edges[e].line) continue;
        in->debouncer.disturbed(now);
        // An e-stop acts on its first active reading, not after the window.
        bool v = false;
        if (in->config.role == GpioInputRole::estop && !read(*in, v)) chip_failed(w);
      }
  }
}

}  // namespace avar::inputs
