#include "avar/firmware_iface/maestro_usb_link.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::firmware_iface {

MaestroUsbLink::MaestroUsbLink(std::unique_ptr<UsbControlTransport> transport, MaestroUsbLinkConfig config)
    : transport_(std::move(transport)), config_(std::move(config)), table_(config_.actuators) {
  if (maestro_usb::product_id_for_channels(config_.channel_count) == 0)
    throw std::invalid_argument("a Maestro has 6, 12, 18 or 24 channels, not " + std::to_string(config_.channel_count));
  check_maestro_channels(config_.actuators, config_.channel_count);
  if (config_.silent_ticks == 0) throw std::invalid_argument("a Maestro on USB needs a silence budget of at least one tick");
  silence_ = DeviceWatch(config_.silent_ticks);
  targets_.resize(config_.actuators.size());
  reply_.resize(maestro_usb::get_positions(config_.channel_count).length);
  description_ = "Maestro (" + std::to_string(config_.channel_count) + " channels) on " + transport_->name();
}

LinkCounters MaestroUsbLink::counters() const noexcept {
  LinkCounters k = counters_.snapshot();
  k.reconnects = reconnector_.reconnects();
  return k;
}

Status MaestroUsbLink::transfer(const UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* got) noexcept {
  const Status s = transport_->control(setup, data, config_.timeout, got);
  counters_.add(&LinkCounters::bytes_sent, 8 + (setup.device_to_host() ? 0 : *got));
  if (setup.device_to_host()) counters_.add(&LinkCounters::bytes_received, *got);
  if (s == Status::timeout) counters_.add(&LinkCounters::timeouts);
  if (s == Status::bad_data) counters_.add(&LinkCounters::device_errors);  // a stalled request
  if (s == Status::io_error) reconnector_.lost();
  return s;
}

Status MaestroUsbLink::read_errors(std::uint16_t& errors) noexcept {
  const UsbSetup setup = maestro_usb::get_variables(config_.channel_count);
  std::array<std::uint8_t, maestro_usb::kMicroVariablesSize + 6 * maestro_usb::kServoRecordSize> reply{};
  std::size_t got = 0;
  if (const Status s = transfer(setup, reply, &got); s != Status::ok) return s;
  if (!maestro_usb::decode_errors(std::span(reply.data(), got), &errors)) return Status::bad_data;
  counters_.add(&LinkCounters::replies);
  return Status::ok;
}

Status MaestroUsbLink::send_limits() noexcept {
  std::size_t got = 0;
  for (const MaestroActuator& a : config_.actuators) {
    const auto ch = static_cast<std::uint8_t>(a.device_channel);
    if (const Status s = transfer(maestro_usb::set_speed(ch, maestro_speed_units(a)), {}, &got); s != Status::ok) return s;
    if (const Status s = transfer(maestro_usb::set_acceleration(ch, maestro_acceleration_units(a)), {}, &got); s != Status::ok)
      return s;
  }
  return Status::ok;
}

Status MaestroUsbLink::start() {
  start_problem_.clear();
  std::uint16_t errors = 0;
  if (const Status s = read_errors(errors); s != Status::ok) {
    start_problem_ = "reading the error register of " + transport_->name() + ": " + std::string(to_string(s));
    return s;
  }
  // Errors latched before this run (a serial timeout, a script that ran over) are history:
  // clear them, as the serial driver's Get Errors does.
  if (errors != 0) start_problem_ = "errors latched before start, cleared: " + maestro::describe_errors(errors);
  std::size_t got = 0;
  if (const Status s = transfer(maestro_usb::clear_errors(), {}, &got); s != Status::ok) return s;
  return send_limits();
}

Status MaestroUsbLink::read_records() noexcept {
  std::size_t got = 0;
  const Status s = transfer(maestro_usb::get_positions(config_.channel_count), reply_, &got);
  if (s != Status::ok) return s;
  if (got != reply_.size()) {
    // A short reply: counted, as a bus counts a broken packet.
    counters_.add(&LinkCounters::framing_errors);
    return Status::bad_data;
  }
  counters_.add(&LinkCounters::replies);
  return Status::ok;
}

Status MaestroUsbLink::read_positions(std::span<double> frame, std::span<bool> known) {
  if (const Status s = read_records(); s != Status::ok) return s;
  for (const MaestroActuator& a : config_.actuators) {
    maestro_usb::ServoStatus status;
    if (!maestro_usb::decode_servo_status(reply_, config_.channel_count, a.device_channel, &status)) return Status::bad_data;
    if (status.position == 0) continue;  // no pulses yet: the device does not know where the servo is
    frame[a.channel] = a.calibration.to_channel(status.position / 4.0);
    known[a.channel] = true;
  }
  return Status::ok;
}

Status MaestroUsbLink::write_targets() noexcept {
  bool reopened = false;
  if (reconnector_.ask(*transport_, &reopened) != Status::ok) return Status::io_error;
  // A Maestro that was unplugged has forgotten its limits.
  if (reopened)
    if (const Status s = send_limits(); s != Status::ok) return s;
  counters_.add(&LinkCounters::exchanges);
  std::size_t got = 0;
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const auto ch = static_cast<std::uint8_t>(config_.actuators[i].device_channel);
    if (const Status s = transfer(maestro_usb::set_target(ch, targets_[i]), {}, &got); s != Status::ok) return s;
  }
  return Status::ok;
}

namespace {
// The pulse widths a Maestro can put out, in its quarter-µs: 64..4080 µs.
constexpr std::uint16_t kLowestPulseQuarterUs = 64 * 4;
constexpr std::uint16_t kHighestPulseQuarterUs = 4080 * 4;
}  // namespace

Status MaestroUsbLink::send(std::span<const double> frame) noexcept {
  for (std::size_t i = 0; i < targets_.size(); ++i) targets_[i] = maestro_target(table_, i, frame);
  Status s = write_targets();
  if (s == Status::ok) s = read_records();
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) {
    maestro_usb::ServoStatus status;
    const MaestroActuator& a = config_.actuators[i];
    if (s != Status::ok || !maestro_usb::decode_servo_status(reply_, config_.channel_count, a.device_channel, &status) ||
        status.position == 0) {
      table_.forget_feedback(i);  // stale feedback is absent, not old
      continue;
    }
    if (status.position < kLowestPulseQuarterUs || status.position > kHighestPulseQuarterUs) {
      // No Maestro puts out such a pulse: the status is noise (the reply has no checksum).
      counters_.add(&LinkCounters::framing_errors);
      table_.forget_feedback(i);
      continue;
    }
    ChannelTelemetry& t = table_.telemetry(i);
    t.position = table_.to_channel(i, status.position / 4.0);
    ++t.updates;
  }
  return judge_silence(s);
}

Status MaestroUsbLink::judge_silence(Status tick) noexcept {
  if (tick == Status::ok) {
    silence_.answered();
    return Status::ok;
  }
  if (tick != Status::timeout && tick != Status::bad_data) return tick;
  // The transfer's own failure is already counted (a timeout, a stall, a short reply).
  return silence_.missed() ? Status::timeout : Status::ok;
}

Status MaestroUsbLink::release() noexcept {
  std::fill(targets_.begin(), targets_.end(), std::uint16_t{0});
  return write_targets();
}

}  // namespace avar::firmware_iface
