#include "avar/firmware_iface/dynamixel_link.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "avar/core/byte_order.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"

namespace avar::firmware_iface {
namespace dxl = dynamixel;
namespace {

constexpr std::size_t kStatusOverhead = 11;                                              // header 7, instruction, error, CRC 2
constexpr std::uint16_t kFullFirst = dxl::kPresentLoad;                                  // 126
constexpr std::uint16_t kFullLength = dxl::kPresentTemperature + 1 - dxl::kPresentLoad;  // 21
constexpr double kPulsesPerRev = 4096;
constexpr double kProfileVelocityUnitRpm = 0.229;
constexpr double kProfileAccelerationUnitRpm2 = 214.577;

std::uint32_t device_faults(std::uint8_t hardware_error) noexcept {
  std::uint32_t f = 0;
  if (hardware_error & 0x01) f |= kDeviceVoltage;
  if (hardware_error & 0x04) f |= kDeviceOverheat;
  if (hardware_error & 0x08) f |= kDeviceEncoder;
  if (hardware_error & 0x10) f |= kDeviceElectrical;
  if (hardware_error & 0x20) f |= kDeviceOverload;
  if (hardware_error & 0xC2) f |= kDeviceOther;
  return f;
}

std::int32_t profile_units(double channel_per_s, double pulses_per_unit, double unit_rpm, double seconds_per_minute) {
  const double rev = channel_per_s * pulses_per_unit / kPulsesPerRev;  // rev/s or rev/s²
  const double per_minute = rev * seconds_per_minute;
  return static_cast<std::int32_t>(std::clamp(std::round(per_minute / unit_rpm), 1.0, 32767.0));
}

/// Checks the IDs before anything is sized; returns them by actuator.
std::vector<std::uint32_t> dynamixel_ids(const DynamixelLinkConfig& config) {
  std::array<bool, 256> used{};
  std::vector<std::uint32_t> ids;
  for (const DynamixelActuator& a : config.actuators) {
    if (a.id > dxl::kMaxId) throw std::invalid_argument("DYNAMIXEL ID " + std::to_string(a.id) + " is outside 0..252");
    if (used[a.id]) throw std::invalid_argument("DYNAMIXEL ID " + std::to_string(a.id) + " is used twice on one bus");
    used[a.id] = true;
    ids.push_back(a.id);
  }
  return ids;
}

BusExchangeConfig dynamixel_exchange(const DynamixelLinkConfig& c) {
  return {c.reply_timeout, c.retries, c.silent_exchanges, c.reconnect_every, DynamixelBusCodec::kMaxPacket};
}

}  // namespace

DynamixelLink::DynamixelLink(ByteTransport& transport, DynamixelLinkConfig config)
    : transport_(transport),
      config_(std::move(config)),
      table_(config_.actuators),
      bus_(transport_, codec_, dynamixel_ids(config_), dynamixel_exchange(config_)) {
  const std::size_t n = config_.actuators.size();
  for (std::size_t i = 0; i < n; ++i) servos_.push_back({config_.actuators[i].id, i});
  std::sort(servos_.begin(), servos_.end(), [](const Servo& a, const Servo& b) { return a.id < b.id; });
  ids_.resize(n);
  values_.resize(n);
  asked_.resize(n);
  // Worst case: every byte stuffed; the largest packet is the Sync Write (4 + 5 per servo).
  packet_.resize(2 * (7 + 3 + 4 + 5 * n) + 64);
  if (config_.readback == DynamixelReadback::position) {
    read_address_ = dxl::kPresentPosition;
    read_length_ = 4;
  } else if (config_.readback == DynamixelReadback::full) {
    read_address_ = kFullFirst;
    read_length_ = kFullLength;
  }
  codec_.set_retry_read(read_address_, read_length_);
  description_ = "DYNAMIXEL 2.0 (" + std::to_string(n) + " servos) on " + transport_.name();
}

Status DynamixelLink::query(const Servo& servo, std::span<const std::uint8_t> request, std::size_t params,
                            std::int32_t* value) noexcept {
  auto take = [&](std::size_t, const BusReply& r) noexcept {
    if (r.params.size() < params) return false;
    if (value) *value = params >= 4 ? dxl::read_i32(r.params) : r.params[0];
    return true;
  };
  return bus_.query(servo.actuator, request, kStatusOverhead + params, take);
}

Status DynamixelLink::write_to(const Servo& servo, std::span<const std::uint8_t> request) noexcept {
  return servo.status_return_level >= 2 ? query(servo, request, 0) : bus_.write(request);
}

Status DynamixelLink::start() {
  start_problem_.clear();
  std::array<std::uint8_t, 64> request{};
  std::int32_t delay = 0, level = 0;
  std::uint32_t longest_delay_us = 0;
  for (Servo& servo : servos_) {
    std::size_t len = dxl::encode_ping(request, servo.id);
    if (const Status s = query(servo, std::span(request.data(), len), 3); s != Status::ok) {
      start_problem_ = "servo ID " + std::to_string(servo.id) + " does not answer a ping (" + std::string(to_string(s)) + ")";
      return s;
    }
    len = dxl::encode_read(request, servo.id, dxl::kReturnDelayTime, 1);
    if (const Status s = query(servo, std::span(request.data(), len), 1, &delay); s != Status::ok) {
      start_problem_ = "servo ID " + std::to_string(servo.id) + " does not answer a read (Status Return Level 0?)";
      return s;
    }
    longest_delay_us = std::max<std::uint32_t>(longest_delay_us, 2u * static_cast<std::uint32_t>(delay));
    len = dxl::encode_read(request, servo.id, dxl::kStatusReturnLevel, 1);
    if (const Status s = query(servo, std::span(request.data(), len), 1, &level); s != Status::ok) return s;
    servo.status_return_level = static_cast<std::uint8_t>(level);
    if (config_.readback != DynamixelReadback::none && servo.status_return_level < 1) {
      start_problem_ = "servo ID " + std::to_string(servo.id) +
                       " has Status Return Level 0 and never answers reads; set it to 1 or 2, or readback: none";
      return Status::out_of_range;
    }
    const DynamixelActuator& a = config_.actuators[servo.actuator];
    const double pulses_per_unit = a.calibration.device_per_unit();
    auto write_i32 = [&](std::uint16_t address, std::int32_t v) {
      std::array<std::uint8_t, 4> data{};
      put_i32_le(data.data(), v);
      return write_to(servo, std::span(request.data(), dxl::encode_write(request, servo.id, address, data)));
    };
    // 0 means "no limit" to the servo, which is also what an absent limit means here.
    const std::int32_t velocity = a.speed_limit ? profile_units(*a.speed_limit, pulses_per_unit, kProfileVelocityUnitRpm, 60) : 0;
    const std::int32_t acceleration =
        a.acceleration_limit ? profile_units(*a.acceleration_limit, pulses_per_unit, kProfileAccelerationUnitRpm2, 3600) : 0;
    if (const Status s = write_i32(dxl::kProfileVelocity, velocity); s != Status::ok) return s;
    if (const Status s = write_i32(dxl::kProfileAcceleration, acceleration); s != Status::ok) return s;
  }
  // Replies start after the Return Delay Time; allow for it on top of the configured timeout.
  bus_.set_reply_timeout(config_.reply_timeout + std::chrono::milliseconds((longest_delay_us + 999) / 1000));
  return enable_torque();
}

Status DynamixelLink::enable_torque() noexcept {
  std::array<std::uint8_t, 32> request{};
  for (const Servo& servo : servos_) {
    if (table_.released(servo.actuator)) continue;
    const std::array<std::uint8_t, 1> on{1};
    if (const Status s = write_to(servo, std::span(request.data(), dxl::encode_write(request, servo.id, dxl::kTorqueEnable, on)));
        s != Status::ok)
      return s;
  }
  return Status::ok;
}

Status DynamixelLink::read_positions(std::span<double> frame, std::span<bool> known) {
  std::array<std::uint8_t, 32> request{};
  for (const Servo& servo : servos_) {
    const std::size_t len = dxl::encode_read(request, servo.id, dxl::kPresentPosition, 4);
    std::int32_t pulses = 0;
    if (const Status s = query(servo, std::span(request.data(), len), 4, &pulses); s != Status::ok) return s;
    frame[table_.channel(servo.actuator)] = table_.to_channel(servo.actuator, pulses);
    known[table_.channel(servo.actuator)] = true;
  }
  return Status::ok;
}

void DynamixelLink::take_reply(Servo& servo, const BusReply& reply) noexcept {
  if (reply.error & 0x80) servo.read_hardware_error = true;
  if (reply.params.size() < read_length_) return;
  ChannelTelemetry& t = table_.telemetry(servo.actuator);
  const std::span<const std::uint8_t> p = reply.params;
  if (read_address_ == dxl::kPresentPosition) {
    t.position = table_.to_channel(servo.actuator, dxl::read_i32(p));
  } else {
    const auto at = [&](std::uint16_t address) { return p.subspan(address - kFullFirst); };
    t.load = static_cast<std::int16_t>(dxl::read_u16(at(dxl::kPresentLoad))) / 1000.0;
    t.position = table_.to_channel(servo.actuator, dxl::read_i32(at(dxl::kPresentPosition)));
    t.temperature_c = at(dxl::kPresentTemperature)[0];
  }
  if (!(reply.error & 0x80)) t.faults = 0;
  ++t.updates;
}

Status DynamixelLink::exchange_telemetry() noexcept {
  std::size_t n = 0;
  for (const Servo& servo : servos_)
    if (!table_.released(servo.actuator)) {
      ids_[n] = servo.id;
      asked_[n++] = servo.actuator;
    }
  const std::span<const std::size_t> asked(asked_.data(), n);
  if (n > 0) {
    const std::size_t len = dxl::encode_sync_read(packet_, read_address_, read_length_, std::span(ids_).first(n));
    if (const Status s = bus_.write(std::span(packet_).first(len)); s != Status::ok) return s;
    auto take = [&](std::size_t slot, const BusReply& r) noexcept {
      for (Servo& servo : servos_)
        if (servo.actuator == slot) take_reply(servo, r);
      return true;
    };
    const std::size_t reply_size = kStatusOverhead + read_length_;
    if (bus_.collect(asked, reply_size, take) == Status::io_error) return Status::io_error;
    if (bus_.retry(asked, reply_size, take) == Status::io_error) return Status::io_error;
  }
  const Status settled = bus_.settle(asked, table_);
  // Alerts: read Hardware Error Status of the servos that raised one.
  for (Servo& servo : servos_) {
    if (!servo.read_hardware_error) continue;
    const std::size_t len = dxl::encode_read(packet_, servo.id, dxl::kHardwareErrorStatus, 1);
    std::int32_t bits = 0;
    const Status s = query(servo, std::span(packet_).first(len), 1, &bits);
    if (s == Status::io_error) return s;
    if (s != Status::ok) continue;  // asked again on the next alert
    servo.read_hardware_error = false;
    table_.telemetry(servo.actuator).faults = device_faults(static_cast<std::uint8_t>(bits));
  }
  return settled;
}

Status DynamixelLink::send(std::span<const double> frame) noexcept {
  bool reopened = false;
  if (bus_.begin(&reopened) != Status::ok) return Status::io_error;
  if (reopened) {
    // A servo that lost power with the adapter comes back with torque off.
    if (const Status s = enable_torque(); s != Status::ok) return s == Status::timeout ? Status::timeout : Status::io_error;
  }
  // Servos released since the last send get Torque Enable = 0, once.
  for (const Servo& servo : servos_) {
    if (!table_.release_pending(servo.actuator)) continue;
    const std::array<std::uint8_t, 1> off{0};
    const Status s = write_to(servo, std::span(packet_).first(dxl::encode_write(packet_, servo.id, dxl::kTorqueEnable, off)));
    if (s == Status::io_error) return s;
    if (s == Status::ok) table_.set_release_told(servo.actuator);
  }
  std::size_t n = 0;
  for (const Servo& servo : servos_) {
    if (table_.released(servo.actuator)) continue;
    ids_[n] = servo.id;
    values_[n] = static_cast<std::int32_t>(std::lround(table_.to_device(servo.actuator, frame)));
    ++n;
  }
  if (n > 0) {
    const std::size_t len =
        dxl::encode_sync_write_u32(packet_, dxl::kGoalPosition, std::span(ids_).first(n), std::span(values_).first(n));
    if (len == 0) return Status::out_of_range;
    if (const Status s = bus_.write(std::span(packet_).first(len)); s != Status::ok) return s;
  }
  if (config_.readback == DynamixelReadback::none) return Status::ok;
  return exchange_telemetry();
}

Status DynamixelLink::release() noexcept {
  // Broadcast Write of Torque Enable = 0: every servo on the bus goes limp, none replies.
  const std::array<std::uint8_t, 1> off{0};
  const std::size_t len = dxl::encode_write(packet_, dxl::kBroadcastId, dxl::kTorqueEnable, off);
  table_.release_all_told();
  return bus_.write(std::span(packet_).first(len));
}

void DynamixelLink::release_channel(std::size_t channel) noexcept { table_.release_channel(channel); }

void DynamixelLink::read_telemetry(std::span<ChannelTelemetry> out) const noexcept { table_.read_telemetry(out); }

LinkCounters DynamixelLink::counters() const noexcept { return bus_.counters(); }

}  // namespace avar::firmware_iface
