#include "avar/session/osc_control.hpp"

#include <lo/lo.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <stdexcept>

#include "avar/control/controller.hpp"

namespace avar::session {
namespace {

constexpr int kOscWaiting = -1;  // phase_ while running but not yet told to play

const char* osc_phase_name(int phase) {
  if (phase == kOscWaiting) return "waiting";
  return control::to_string(static_cast<control::Phase>(phase));
}

/// One argument as a number (int or float types); false otherwise.
bool osc_number(char type, const lo_arg* arg, double& value) {
  switch (type) {
    case LO_FLOAT: {
      float f;
      std::memcpy(&f, arg, sizeof f);
      value = f;
      return true;
    }
    case LO_DOUBLE: std::memcpy(&value, arg, sizeof value); return true;
    case LO_INT32: {
      std::int32_t i;
      std::memcpy(&i, arg, sizeof i);
      value = i;
      return true;
    }
    default: return false;
  }
}

}  // namespace

std::pair<std::string, std::uint16_t> parse_osc_control_address(const std::string& text) {
  const auto colon = text.rfind(':');
  const std::string host = colon == std::string::npos ? "127.0.0.1" : text.substr(0, colon);
  const std::string port = colon == std::string::npos ? text : text.substr(colon + 1);
  unsigned value = 0;
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || error != std::errc{} || end != port.data() + port.size() || value > 65535)
    throw std::invalid_argument("--osc-control '" + text + "': expected [ADDRESS:]PORT, e.g. 9001 or 127.0.0.1:9001");
  return {host, static_cast<std::uint16_t>(value)};
}

OscControlSurface::OscControlSurface(const std::string& address, std::string show_name)
    : listener_(parse_osc_control_address(address).first, parse_osc_control_address(address).second, "OSC control"),
      show_name_(std::move(show_name)) {}

OscControlSurface::~OscControlSurface() { stop(); }

void OscControlSurface::start() {
  listener_.start([this](std::span<const std::uint8_t> datagram, std::int64_t) { handle(datagram); });
}

void OscControlSurface::stop() noexcept { listener_.stop(); }

void OscControlSurface::handle(std::span<const std::uint8_t> datagram) noexcept {
  int result = 0;
  void* bytes = const_cast<std::uint8_t*>(datagram.data());  // deserialise copies before it swaps
  lo_message message = datagram.empty() ? nullptr : lo_message_deserialise(bytes, datagram.size(), &result);
  if (message == nullptr) {
    ignored_.fetch_add(1, std::memory_order_relaxed);
    return reply_error("not an OSC message");
  }
  const std::string path = lo_get_path(bytes, static_cast<ssize_t>(datagram.size()));
  const char* types = lo_message_get_types(message);
  const int argc = lo_message_get_argc(message);
  lo_arg** argv = lo_message_get_argv(message);
  std::string error;
  if (path == "/avar/show/play") {
    if (argc == 1 && types[0] == LO_STRING && show_name_ == reinterpret_cast<const char*>(argv[0])) play_.store(true);
    else error = "/avar/show/play takes the show's name: '" + show_name_ + "'";
  } else if (path == "/avar/show/stop") {
    stop_.store(true);
  } else if (path == "/avar/show/seek") {
    double seconds = 0;
    if (argc == 1 && osc_number(types[0], argv[0], seconds) && seconds >= 0 && std::isfinite(seconds)) {
      seek_to_.store(seconds);
      seek_requests_.fetch_add(1, std::memory_order_release);
    } else {
      error = "/avar/show/seek takes one number of seconds >= 0";
    }
  } else if (path == "/avar/estop") {
    estop_.store(true);
  } else if (path != "/avar/state") {
    error = "unknown address " + path + " (expected /avar/show/play, /avar/show/stop, /avar/show/seek, /avar/estop, /avar/state)";
  }
  lo_message_free(message);
  if (!error.empty()) {
    ignored_.fetch_add(1, std::memory_order_relaxed);
    return reply_error(error);
  }
  commands_.fetch_add(1, std::memory_order_relaxed);
  reply_state();
}

void OscControlSurface::send_reply(void* message, const char* path) noexcept {
  auto* m = static_cast<lo_message>(message);
  std::size_t size = 0;
  void* data = lo_message_serialise(m, path, nullptr, &size);
  if (data) (void)listener_.reply_to_sender(std::span(static_cast<const std::uint8_t*>(data), size));
  std::free(data);
  lo_message_free(m);
}

void OscControlSurface::reply_state() noexcept {
  lo_message m = lo_message_new();
  lo_message_add_string(m, osc_phase_name(phase_.load()));
  lo_message_add_float(m, static_cast<float>(show_time_.load()));
  lo_message_add_string(m, show_name_.c_str());
  send_reply(m, "/avar/state");
}

void OscControlSurface::reply_error(const std::string& why) noexcept {
  lo_message m = lo_message_new();
  lo_message_add_string(m, why.c_str());
  send_reply(m, "/avar/error");
}

control::ShowClockReading OscControlSurface::read(double now_s) noexcept {
  if (stop_.load(std::memory_order_relaxed)) return {base_show_s_ + (started_ ? now_s - base_now_s_ : 0.0), true};
  if (!started_ && play_.load(std::memory_order_relaxed)) {
    started_ = true;
    base_now_s_ = now_s;
  }
  const std::uint64_t seeks = seek_requests_.load(std::memory_order_acquire);
  if (seeks != seeks_seen_) {
    seeks_seen_ = seeks;
    base_show_s_ = seek_to_.load(std::memory_order_relaxed);
    base_now_s_ = now_s;
  }
  return {started_ ? base_show_s_ + (now_s - base_now_s_) : base_show_s_, false};
}

void OscControlSurface::after_tick(std::uint64_t tick, double now_s, double dt_s, double lateness_s,
                                   control::Controller& controller) {
  const control::Phase p = controller.phase();
  phase_.store(p == control::Phase::running && !started_ ? kOscWaiting : static_cast<int>(p), std::memory_order_relaxed);
  show_time_.store(controller.show_time(), std::memory_order_relaxed);
  if (inner_) inner_->after_tick(tick, now_s, dt_s, lateness_s, controller);
}

void OscControlSurface::summarize(std::ostream& out) const {
  out << "OSC control on udp " << listener_.where() << ": " << commands_.load() << " commands, " << ignored_.load()
      << " ignored\n";
}

}  // namespace avar::session
