#include "avar/sim/sim_slcan_adapter.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

#include "avar/firmware_iface/slcan_codec.hpp"
#include "avar/sim/reply_queue.hpp"

namespace avar::sim {
namespace {

namespace slcan = firmware_iface::slcan;
using firmware_iface::CanFrame;

/// Longer command lines are refused whole (the longest valid one is 27 characters).
constexpr std::size_t kMaxCommand = 64;

SimCanBusConfig instant_bus(const SimSlcanConfig& config) {
  SimCanBusConfig bus;
  bus.bitrate = config.bus_bitrate;
  bus.timing = SimCanTiming::instant;
  bus.idle_step_s = config.idle_step_s;
  return bus;
}

/// Error counters that go with an error state, for the `s` line.
int tx_errors_of(std::uint32_t classes) {
  if (classes & firmware_iface::kCanErrorBusOff) return 256;
  if (classes & firmware_iface::kCanErrorPassive) return 128;
  if (classes & firmware_iface::kCanErrorWarning) return 96;
  return 0;
}

}  // namespace

SimSlcanAdapter::SimSlcanAdapter(SimSlcanConfig config, const std::vector<CanNode*>& nodes)
    : config_(std::move(config)), bus_(instant_bus(config_), nodes), code_(config_.initial_code) {
  bus_.set_host_online(false);  // closed until `O` or `L`
  line_.reserve(kMaxCommand);
}

void SimSlcanAdapter::receive(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) {
    ++bytes_received_;
    if (b != slcan::kCr) {
      if (line_.size() < kMaxCommand) line_.push_back(b);
      else line_too_long_ = true;
      continue;
    }
    if (line_too_long_) bell();
    else command(line_);
    line_.clear();
    line_too_long_ = false;
  }
}

std::size_t SimSlcanAdapter::take_replies(std::span<std::uint8_t> out) { return take_from(replies_, out); }

void SimSlcanAdapter::advance(double dt_s) {
  bus_.run_until(bus_.now_s() + std::max(dt_s, 0.0));
  flush_bus();
}

void SimSlcanAdapter::reply(std::string_view text) { replies_.insert(replies_.end(), text.begin(), text.end()); }

void SimSlcanAdapter::bell() {
  ++refused_;
  replies_.push_back(slcan::kBel);
}

bool SimSlcanAdapter::bitrate_matches() const noexcept { return code_ >= 0 && slcan::bitrate_of_code(code_) == bus_.bitrate(); }

void SimSlcanAdapter::set_open(bool open, bool listen_only) {
  open_ = open;
  listen_only_ = listen_only;
  bus_.set_host_online(open);
  if (open) {
    bus_.restart_host();  // opening resets the controller, bus-off included
    flags_ = 0;
  }
}

void SimSlcanAdapter::command(std::span<const std::uint8_t> line) {
  if (line.empty()) return ok();
  const std::size_t n = line.size();
  const std::uint8_t letter = line[0];
  const auto hex = [&](std::size_t i) {
    const std::uint8_t c = line[i];
    return (c >= '0' && c <= '9') || (c >= 'A' && c <= 'F') || (c >= 'a' && c <= 'f');
  };
  switch (letter) {
    case 'S':
      if (open_ || n != 2 || line[1] < '0' || line[1] > '8') return bell();
      code_ = line[1] - '0';
      return ok();
    case 's':
      if (open_ || n != 5 || !hex(1) || !hex(2) || !hex(3) || !hex(4)) return bell();
      code_ = -1;  // custom bit timing: not modelled, so it matches no bus
      return ok();
    case 'O':
    case 'L':
      if (open_ || n != 1) return bell();
      set_open(true, letter == 'L');
      return ok();
    case 'C':
      if (!open_ || n != 1) return bell();
      set_open(false, false);
      return ok();
    case 't':
    case 'T':
    case 'r':
    case 'R': return transmit(line);
    case 'F': {
      if (!open_ || n != 1) return bell();
      flush_bus();
      std::array<char, 8> text{};
      std::snprintf(text.data(), text.size(), "F%02X\r", flags_);
      flags_ = 0;
      return reply(text.data());
    }
    case 'Z':
      if (n != 2 || (line[1] != '0' && line[1] != '1')) return bell();
      timestamps_ = line[1] == '1';
      return ok();
    case 'V':
      if (n != 1) return bell();
      reply(config_.version);
      return ok();
    case 'N':
      if (n != 1) return bell();
      reply(config_.serial);
      return ok();
    default: return bell();
  }
}

void SimSlcanAdapter::transmit(std::span<const std::uint8_t> line) {
  if (!open_ || listen_only_ || bus_.host_bus_off()) return bell();
  const slcan::Line parsed = slcan::parse_line(line);
  if (parsed.kind != slcan::LineKind::frame || parsed.timestamp_ms >= 0) return bell();
  if (!bitrate_matches()) {
    // Nobody on the bus understands the adapter's bits: error frames instead of a frame.
    reply(config_.transmit_acks ? (parsed.frame.extended ? "Z\r" : "z\r") : "\r");
    bus_.inject_error(firmware_iface::kCanErrorProtocol);
    return flush_bus();
  }
  if (bus_.host_send(parsed.frame) != Status::ok) return bell();
  ++transmitted_;
  bus_.run_until(bus_.now_s());
  reply(config_.transmit_acks ? (parsed.frame.extended ? "Z\r" : "z\r") : "\r");
  flush_bus();
}

void SimSlcanAdapter::flush_bus() {
  std::array<std::uint8_t, 2 * slcan::kMaxLineLength> text{};
  CanFrame f;
  while (bus_.host_receive(&f)) {
    if (!open_) continue;
    if (f.error) {
      flags_ |= slcan::status_of_error_classes(f.id);
      if (!config_.linux_error_lines) continue;
      const std::size_t len = slcan::encode_error_lines(text, f, 0, tx_errors_of(f.id));
      replies_.insert(replies_.end(), text.begin(), text.begin() + static_cast<long>(len));
      continue;
    }
    if (!bitrate_matches()) continue;
    const int ms = timestamps_ ? static_cast<int>((f.timestamp.count() / 1'000'000) % slcan::kTimestampModulo) : -1;
    const std::size_t len = slcan::encode_frame(text, f, ms);
    replies_.insert(replies_.end(), text.begin(), text.begin() + static_cast<long>(len));
  }
  if (const std::uint64_t overruns = bus_.statistics().host_overruns; overruns != overruns_seen_) {
    flags_ |= slcan::kDataOverrun;
    overruns_seen_ = overruns;
  }
}

}  // namespace avar::sim
