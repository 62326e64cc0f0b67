#include "avar/firmware_iface/dynamixel_link.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "avar/firmware_iface/dynamixel_codec.hpp"

namespace avar::firmware_iface {
namespace dxl = dynamixel;
namespace {

constexpr std::size_t kHeader = 7;  // FF FF FD 00 ID LEN_L LEN_H
constexpr std::uint16_t kFullFirst = dxl::kPresentLoad;                                   // 126
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

}  // namespace

DynamixelLink::DynamixelLink(ByteTransport& transport, DynamixelLinkConfig config)
    : transport_(transport), config_(std::move(config)), reconnector_(config_.reconnect_every) {
  const std::size_t n = config_.actuators.size();
  std::array<bool, 256> used{};
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t id = config_.actuators[i].id;
    if (id > dxl::kMaxId) throw std::invalid_argument("DYNAMIXEL ID " + std::to_string(id) + " is outside 0..252");
    if (used[id]) throw std::invalid_argument("DYNAMIXEL ID " + std::to_string(id) + " is used twice on one bus");
    used[id] = true;
    servos_.push_back({id, i});
  }
  std::sort(servos_.begin(), servos_.end(), [](const Servo& a, const Servo& b) { return a.id < b.id; });
  telemetry_.resize(n);
  released_ = std::make_unique<std::atomic<bool>[]>(n);
  ids_.resize(n);
  values_.resize(n);
  // Worst case: every byte stuffed; the largest packet is the Sync Write (4 + 5 per servo).
  packet_.resize(2 * (kHeader + 3 + 4 + 5 * n) + 64);
  rx_.resize(1024);
  scratch_.resize(1024);
  if (config_.readback == DynamixelReadback::position) {
    read_address_ = dxl::kPresentPosition;
    read_length_ = 4;
  } else if (config_.readback == DynamixelReadback::full) {
    read_address_ = kFullFirst;
    read_length_ = kFullLength;
  }
  timeout_ = config_.reply_timeout;
  description_ = "DYNAMIXEL 2.0 (" + std::to_string(n) + " servos) on " + transport_.name();
}

Status DynamixelLink::write_counted(std::span<const std::uint8_t> bytes) noexcept {
  const Status s = transport_.write(bytes);
  if (s == Status::ok) {
    counters_.bytes_sent.fetch_add(bytes.size(), std::memory_order_relaxed);
    last_exchange_bytes_ += bytes.size();
  } else if (s == Status::io_error) {
    reconnector_.lost();
  }
  return s;
}

Status DynamixelLink::read_status(std::uint8_t* id, std::uint8_t* error, std::chrono::milliseconds timeout) noexcept {
  for (;;) {
    std::size_t need = kHeader;
    if (rx_size_ >= kHeader) need = kHeader + dxl::read_u16(std::span(rx_).subspan(5, 2));
    if (rx_size_ > 0) {
      dxl::Status status;
      std::size_t consumed = 0;
      const dxl::DecodeResult r = dxl::decode_status(std::span(rx_).first(rx_size_), scratch_, &status, &consumed);
      if (consumed > 0) {
        std::memmove(rx_.data(), rx_.data() + consumed, rx_size_ - consumed);
        rx_size_ -= consumed;
      }
      switch (r) {
        case dxl::DecodeResult::ok:
          counters_.replies.fetch_add(1, std::memory_order_relaxed);
          *id = status.id;
          *error = status.error;
          status_params_ = status.params;
          return Status::ok;
        case dxl::DecodeResult::bad_crc: counters_.crc_errors.fetch_add(1, std::memory_order_relaxed); return Status::bad_data;
        case dxl::DecodeResult::bad_framing:
          counters_.framing_errors.fetch_add(consumed, std::memory_order_relaxed);
          continue;
        case dxl::DecodeResult::not_status: continue;  // an echo of our own request on a shared line
        case dxl::DecodeResult::need_more: break;
      }
    }
    if (need <= rx_size_ || need > rx_.size()) {
      // A length no reply of ours can have: drop a byte and look for the next header.
      counters_.framing_errors.fetch_add(1, std::memory_order_relaxed);
      std::memmove(rx_.data(), rx_.data() + 1, rx_size_ - 1);
      --rx_size_;
      continue;
    }
    const Status s = transport_.read_exact(std::span(rx_).subspan(rx_size_, need - rx_size_), timeout);
    if (s == Status::io_error) reconnector_.lost();
    if (s != Status::ok) {
      if (s == Status::timeout) counters_.timeouts.fetch_add(1, std::memory_order_relaxed);
      rx_size_ = 0;  // the transport discarded the partial read
      return s;
    }
    counters_.bytes_received.fetch_add(need - rx_size_, std::memory_order_relaxed);
    last_exchange_bytes_ += need - rx_size_;
    rx_size_ = need;
  }
}

Status DynamixelLink::query(std::span<const std::uint8_t> request, std::uint8_t id, std::uint8_t* error) noexcept {
  transport_.discard_input();
  rx_size_ = 0;
  if (const Status s = write_counted(request); s != Status::ok) return s;
  for (;;) {
    std::uint8_t from = 0;
    if (const Status s = read_status(&from, error, timeout_); s != Status::ok) return s;
    if (from == id) return Status::ok;
  }
}

Status DynamixelLink::start() {
  start_problem_.clear();
  std::array<std::uint8_t, 64> request{};
  std::uint8_t error = 0;
  std::uint32_t longest_delay_us = 0;
  for (Servo& servo : servos_) {
    std::size_t len = dxl::encode_ping(request, servo.id);
    if (const Status s = query(std::span(request.data(), len), servo.id, &error); s != Status::ok) {
      start_problem_ = "servo ID " + std::to_string(servo.id) + " does not answer a ping (" + std::string(to_string(s)) + ")";
      return s;
    }
    len = dxl::encode_read(request, servo.id, dxl::kReturnDelayTime, 1);
    if (const Status s = query(std::span(request.data(), len), servo.id, &error); s != Status::ok) {
      start_problem_ = "servo ID " + std::to_string(servo.id) + " does not answer a read (Status Return Level 0?)";
      return s;
    }
    longest_delay_us = std::max<std::uint32_t>(longest_delay_us, 2u * status_params_[0]);
    len = dxl::encode_read(request, servo.id, dxl::kStatusReturnLevel, 1);
    if (const Status s = query(std::span(request.data(), len), servo.id, &error); s != Status::ok) return s;
    servo.status_return_level = status_params_[0];
    if (config_.readback != DynamixelReadback::none && servo.status_return_level < 1) {
      start_problem_ = "servo ID " + std::to_string(servo.id) +
                       " has Status Return Level 0 and never answers reads; set it to 1 or 2, or readback: none";
      return Status::out_of_range;
    }
    const DynamixelActuator& a = config_.actuators[servo.actuator];
    const double pulses_per_unit = a.calibration.device_per_unit();
    auto write_i32 = [&](std::uint16_t address, std::int32_t v) {
      const std::array<std::uint8_t, 4> data{static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                             static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 24)};
      const std::size_t n = dxl::encode_write(request, servo.id, address, data);
      if (servo.status_return_level >= 2) return query(std::span(request.data(), n), servo.id, &error);
      return write_counted(std::span(request.data(), n));
    };
    // 0 means "no limit" to the servo, which is also what an absent limit means here.
    const std::int32_t velocity =
        a.speed_limit ? profile_units(*a.speed_limit, pulses_per_unit, kProfileVelocityUnitRpm, 60) : 0;
    const std::int32_t acceleration =
        a.acceleration_limit ? profile_units(*a.acceleration_limit, pulses_per_unit, kProfileAccelerationUnitRpm2, 3600) : 0;
    if (const Status s = write_i32(dxl::kProfileVelocity, velocity); s != Status::ok) return s;
    if (const Status s = write_i32(dxl::kProfileAcceleration, acceleration); s != Status::ok) return s;
  }
  // Replies start after the Return Delay Time; allow for it on top of the configured timeout.
  timeout_ = config_.reply_timeout + std::chrono::milliseconds((longest_delay_us + 999) / 1000);
  return enable_torque();
}

Status DynamixelLink::enable_torque() noexcept {
  std::array<std::uint8_t, 32> request{};
  std::uint8_t error = 0;
  for (Servo& servo : servos_) {
    if (released_[servo.actuator].load(std::memory_order_relaxed)) continue;
    const std::array<std::uint8_t, 1> on{1};
    const std::size_t len = dxl::encode_write(request, servo.id, dxl::kTorqueEnable, on);
    const Status s = servo.status_return_level >= 2 ? query(std::span(request.data(), len), servo.id, &error)
                                                    : write_counted(std::span(request.data(), len));
    if (s != Status::ok) return s;
  }
  return Status::ok;
}

Status DynamixelLink::read_positions(std::span<double> frame, std::span<bool> known) {
  std::array<std::uint8_t, 32> request{};
  std::uint8_t error = 0;
  for (const Servo& servo : servos_) {
    const std::size_t len = dxl::encode_read(request, servo.id, dxl::kPresentPosition, 4);
    if (const Status s = query(std::span(request.data(), len), servo.id, &error); s != Status::ok) return s;
    if (status_params_.size() < 4) return Status::bad_data;
    const DynamixelActuator& a = config_.actuators[servo.actuator];
    frame[a.channel] = a.calibration.to_channel(dxl::read_i32(status_params_));
    known[a.channel] = true;
  }
  return Status::ok;
}

void DynamixelLink::take_reply(Servo& servo, std::uint8_t error) noexcept {
  servo.answered = true;
  servo.missed = 0;
  if (error & 0x7F) counters_.device_errors.fetch_add(1, std::memory_order_relaxed);
  if (error & 0x80) servo.read_hardware_error = true;
  if (status_params_.size() < read_length_) return;
  const DynamixelActuator& a = config_.actuators[servo.actuator];
  ChannelTelemetry& t = telemetry_[servo.actuator];
  const std::span<const std::uint8_t> p = status_params_;
  if (read_address_ == dxl::kPresentPosition) {
    t.position = a.calibration.to_channel(dxl::read_i32(p));
  } else {
    const auto at = [&](std::uint16_t address) { return p.subspan(address - kFullFirst); };
    t.load = static_cast<std::int16_t>(dxl::read_u16(at(dxl::kPresentLoad))) / 1000.0;
    t.position = a.calibration.to_channel(dxl::read_i32(at(dxl::kPresentPosition)));
    t.temperature_c = at(dxl::kPresentTemperature)[0];
  }
  if (!(error & 0x80)) t.faults = 0;
  ++t.updates;
}

Status DynamixelLink::exchange_telemetry() noexcept {
  std::uint8_t error = 0;
  std::size_t n = 0;
  for (Servo& servo : servos_) {
    servo.answered = false;
    if (!released_[servo.actuator].load(std::memory_order_relaxed)) ids_[n++] = servo.id;
  }
  if (n == 0) return Status::ok;
  std::size_t len = dxl::encode_sync_read(packet_, read_address_, read_length_, std::span(ids_).first(n));
  if (const Status s = write_counted(std::span(packet_).first(len)); s != Status::ok) return s;
  std::size_t expected = n;
  while (expected > 0) {
    std::uint8_t id = 0;
    const Status s = read_status(&id, &error, timeout_);
    if (s == Status::io_error) return s;
    if (s == Status::timeout) break;  // the rest would time out too: retry them below
    if (s != Status::ok) {
      --expected;  // a corrupt reply: its servo is retried below
      continue;
    }
    for (Servo& servo : servos_)
      if (servo.id == id && !servo.answered) {
        take_reply(servo, error);
        --expected;
      }
  }
  // Bounded retries for servos whose reply was lost, each by a plain Read.
  std::uint32_t retries = config_.retries;
  for (Servo& servo : servos_) {
    if (servo.answered || released_[servo.actuator].load(std::memory_order_relaxed)) continue;
    if (retries > 0) {
      --retries;
      counters_.retries.fetch_add(1, std::memory_order_relaxed);
      len = dxl::encode_read(packet_, servo.id, read_address_, read_length_);
      const Status s = query(std::span(packet_).first(len), servo.id, &error);
      if (s == Status::io_error) return s;
      if (s == Status::ok) {
        take_reply(servo, error);
        continue;
      }
    }
    ++servo.missed;
  }
  // Alerts: read Hardware Error Status of the servos that raised one.
  for (Servo& servo : servos_) {
    if (!servo.read_hardware_error) continue;
    len = dxl::encode_read(packet_, servo.id, dxl::kHardwareErrorStatus, 1);
    const Status s = query(std::span(packet_).first(len), servo.id, &error);
    if (s == Status::io_error) return s;
    if (s != Status::ok || status_params_.empty()) continue;  // asked again on the next alert
    servo.read_hardware_error = false;
    telemetry_[servo.actuator].faults = device_faults(status_params_[0]);
  }
  for (const Servo& servo : servos_)
    if (servo.missed >= config_.silent_exchanges) return Status::timeout;
  return Status::ok;
}

Status DynamixelLink::send(std::span<const double> frame) noexcept {
  last_exchange_bytes_ = 0;
  bool reopened = false;
  if (reconnector_.ask(transport_, &reopened) != Status::ok) return Status::io_error;
  if (reopened) {
    // A servo that lost power with the adapter comes back with torque off.
    if (const Status s = enable_torque(); s != Status::ok) return s == Status::timeout ? Status::timeout : Status::io_error;
  }
  transport_.discard_input();
  rx_size_ = 0;
  counters_.exchanges.fetch_add(1, std::memory_order_relaxed);
  std::uint8_t error = 0;
  // Servos released since the last send get Torque Enable = 0, once.
  for (Servo& servo : servos_) {
    if (!released_[servo.actuator].load(std::memory_order_relaxed) || servo.torque_off_sent) continue;
    const std::array<std::uint8_t, 1> off{0};
    const std::size_t len = dxl::encode_write(packet_, servo.id, dxl::kTorqueEnable, off);
    const Status s = servo.status_return_level >= 2 ? query(std::span(packet_).first(len), servo.id, &error)
                                                    : write_counted(std::span(packet_).first(len));
    if (s == Status::io_error) return s;
    if (s == Status::ok) servo.torque_off_sent = true;
  }
  std::size_t n = 0;
  for (const Servo& servo : servos_) {
    if (released_[servo.actuator].load(std::memory_order_relaxed)) continue;
    const DynamixelActuator& a = config_.actuators[servo.actuator];
    bool clamped = false;
    const double pulses = a.calibration.to_device(frame[a.channel], &clamped);
    if (clamped) saturated_.fetch_add(1, std::memory_order_relaxed);
    ids_[n] = servo.id;
    values_[n] = static_cast<std::int32_t>(std::lround(pulses));
    ++n;
  }
  if (n > 0) {
    const std::size_t len =
        dxl::encode_sync_write_u32(packet_, dxl::kGoalPosition, std::span(ids_).first(n), std::span(values_).first(n));
    if (len == 0) return Status::out_of_range;
    if (const Status s = write_counted(std::span(packet_).first(len)); s != Status::ok) return s;
  }
  if (config_.readback == DynamixelReadback::none) return Status::ok;
  return exchange_telemetry();
}

Status DynamixelLink::release() noexcept {
  // Broadcast Write of Torque Enable = 0: every servo on the bus goes limp, none replies.
  const std::array<std::uint8_t, 1> off{0};
  const std::size_t len = dxl::encode_write(packet_, dxl::kBroadcastId, dxl::kTorqueEnable, off);
  for (std::size_t i = 0; i < servos_.size(); ++i) released_[i].store(true, std::memory_order_relaxed);
  for (Servo& servo : servos_) servo.torque_off_sent = true;
  return write_counted(std::span(packet_).first(len));
}

void DynamixelLink::release_channel(std::size_t channel) noexcept {
  for (std::size_t i = 0; i < config_.actuators.size(); ++i)
    if (config_.actuators[i].channel == channel) released_[i].store(true, std::memory_order_relaxed);
}

void DynamixelLink::read_telemetry(std::span<ChannelTelemetry> out) const noexcept {
  for (std::size_t i = 0; i < config_.actuators.size(); ++i) out[config_.actuators[i].channel] = telemetry_[i];
}

LinkCounters DynamixelLink::counters() const noexcept {
  LinkCounters k = counters_.snapshot();
  k.reconnects = reconnector_.reconnects();
  return k;
}

}  // namespace avar::firmware_iface
