#include "avar/sim/sim_dynamixel.hpp"

#include <algorithm>
#include <cmath>

#include "avar/core/byte_order.hpp"
#include "avar/firmware_iface/dynamixel_codec.hpp"

namespace avar::sim {
namespace dxl = firmware_iface::dynamixel;
namespace {

// Processing errors of the status packet's error byte.
constexpr std::uint8_t kInstructionError = 0x02;
constexpr std::uint8_t kCrcError = 0x03;
constexpr std::uint8_t kDataRangeError = 0x04;
constexpr std::uint8_t kDataLimitError = 0x06;
constexpr std::uint8_t kAccessError = 0x07;
constexpr std::uint8_t kAlert = 0x80;

constexpr std::uint16_t kEepromEnd = 64;            // addresses below: EEPROM, writable only with torque off
constexpr std::uint16_t kTemperatureLimit = 31;
constexpr std::uint16_t kMaxPositionLimit = 48;
constexpr std::uint16_t kMinPositionLimit = 52;
constexpr std::uint16_t kShutdown = 63;
constexpr std::uint16_t kMoving = 122;
constexpr std::uint16_t kPresentVelocity = 128;
constexpr std::uint8_t kOverheating = 0x04;

/// Which control-table bytes are read-only (model number, firmware, and the whole RAM status area).
bool read_only(std::uint16_t address) {
  return address < 7 || address == 69 || address == dxl::kHardwareErrorStatus || (address >= 120 && address < 168);
}

}  // namespace

SimDynamixel::SimDynamixel(SimDynamixelConfig config) : config_(std::move(config)) {
  for (const SimDynamixelServo& spec : config_.servos) {
    Servo s;
    s.spec = spec;
    s.model = SmartServoModel({spec.max_speed_pulses_per_s, spec.max_acceleration_pulses_per_s2, spec.time_constant_s, 0,
                               spec.ambient_c, spec.heating_c_per_s_at_full_load, spec.cooling_per_s},
                              spec.initial_position);
    write_u16(s, dxl::kModelNumber, spec.model_number);
    s.table[6] = spec.firmware;
    s.table[dxl::kId] = spec.id;
    s.table[dxl::kBaudRate] = 3;  // 1 Mbit/s
    s.table[dxl::kReturnDelayTime] = 0;
    s.table[dxl::kOperatingMode] = 3;  // position control
    s.table[kTemperatureLimit] = 80;
    write_i32(s, kMaxPositionLimit, 4095);
    write_i32(s, kMinPositionLimit, 0);
    s.table[kShutdown] = 52;  // overheating, electrical shock, overload
    s.table[dxl::kStatusReturnLevel] = 2;
    write_i32(s, dxl::kGoalPosition, spec.initial_position);
    write_i32(s, dxl::kPresentPosition, spec.initial_position);
    s.table[dxl::kPresentTemperature] = static_cast<std::uint8_t>(std::lround(spec.ambient_c));
    servos_.push_back(s);
  }
  input_.reserve(4096);
  scratch_.resize(4096);
}

std::int32_t SimDynamixel::read_i32(std::size_t servo, std::uint16_t address) const {
  return dxl::read_i32(std::span(servos_[servo].table).subspan(address, 4));
}

void SimDynamixel::write_i32(Servo& s, std::uint16_t address, std::int32_t v) { put_i32_le(&s.table[address], v); }

void SimDynamixel::write_u16(Servo& s, std::uint16_t address, std::uint16_t v) { put_u16_le(&s.table[address], v); }

SimDynamixel::Servo* SimDynamixel::find(std::uint8_t id) {
  for (Servo& s : servos_)
    if (s.table[dxl::kId] == id) return &s;
  return nullptr;
}

std::uint8_t SimDynamixel::status_error(const Servo& s, std::uint8_t processing) const {
  return static_cast<std::uint8_t>(processing | (s.table[dxl::kHardwareErrorStatus] ? kAlert : 0));
}

void SimDynamixel::reply(const Servo& s, std::uint8_t error, std::span<const std::uint8_t> params) {
  std::array<std::uint8_t, 1 + 64> body{};
  body[0] = status_error(s, error);
  std::copy(params.begin(), params.end(), body.begin() + 1);
  std::array<std::uint8_t, 160> packet{};
  const std::size_t n =
      dxl::encode_instruction(packet, s.table[dxl::kId], dxl::kStatus, std::span(body.data(), 1 + params.size()));
  replies_.insert(replies_.end(), packet.begin(), packet.begin() + static_cast<long>(n));
}

std::uint8_t SimDynamixel::write(Servo& s, std::uint16_t address, std::span<const std::uint8_t> data) {
  if (data.empty() || address + data.size() > kTableSize) return kAccessError;
  for (std::size_t i = 0; i < data.size(); ++i)
    if (read_only(static_cast<std::uint16_t>(address + i))) return kAccessError;
  if (address < kEepromEnd && s.table[dxl::kTorqueEnable]) return kAccessError;
  if (address == dxl::kGoalPosition) {
    if (data.size() != 4) return 0x05;  // data length error
    const std::int32_t goal = dxl::read_i32(data);
    if (goal < read_i32(static_cast<std::size_t>(&s - servos_.data()), kMinPositionLimit) ||
        goal > read_i32(static_cast<std::size_t>(&s - servos_.data()), kMaxPositionLimit))
      return kDataLimitError;
  }
  if (address == dxl::kTorqueEnable && data[0] > 1) return kDataRangeError;
  if (address == dxl::kTorqueEnable && data[0] == 1 && (s.table[dxl::kHardwareErrorStatus] & s.table[kShutdown]))
    return kAccessError;  // after a shutdown only a reboot re-allows torque
  if (address == dxl::kStatusReturnLevel && data[0] > 2) return kDataRangeError;
  std::copy(data.begin(), data.end(), s.table.begin() + address);
  return 0;
}

void SimDynamixel::receive(std::span<const std::uint8_t> bytes) {
  bytes_received_ += bytes.size();
  input_.insert(input_.end(), bytes.begin(), bytes.end());
  std::size_t at = 0;
  for (;;) {
    dxl::Packet packet;
    std::size_t used = 0;
    const dxl::DecodeResult r = dxl::decode_packet(std::span(input_).subspan(at), scratch_, &packet, &used);
    at += used;
    if (r == dxl::DecodeResult::need_more) break;
    if (r == dxl::DecodeResult::bad_crc) {
      ++crc_errors_;
      // The addressed servo answers a CRC error (never to a broadcast).
      const std::uint8_t id = input_[at - used + 4];
      if (Servo* s = find(id)) reply(*s, kCrcError, {});
      continue;
    }
    if (r != dxl::DecodeResult::ok) continue;
    if (packet.instruction == dxl::kStatus) continue;  // another device's answer on the bus
    if (config_.log_limit) {
      log_.push_back({packet.id, packet.instruction, std::vector<std::uint8_t>(packet.params.begin(), packet.params.end())});
      if (log_.size() > config_.log_limit) log_.pop_front();
    }
    handle(packet.id, packet.instruction, packet.params);
  }
  input_.erase(input_.begin(), input_.begin() + static_cast<long>(at));
}

void SimDynamixel::handle(std::uint8_t id, std::uint8_t instruction, std::span<const std::uint8_t> params) {
  const bool broadcast = id == dxl::kBroadcastId;
  const auto for_each_target = [&](auto&& f) {
    if (broadcast) {
      for (Servo& s : servos_) f(s);
    } else if (Servo* s = find(id)) {
      f(*s);
    }
  };
  // Status Return Level: 0 answers Ping only, 1 also Read, 2 everything.
  const auto answers = [](const Servo& s, std::uint8_t instr) {
    const std::uint8_t level = s.table[dxl::kStatusReturnLevel];
    return instr == dxl::kPing || level >= 2 || (level == 1 && (instr == dxl::kRead || instr == dxl::kSyncRead));
  };
  switch (instruction) {
    case dxl::kPing:
      for_each_target([&](Servo& s) {
        const std::uint8_t p[3] = {s.table[0], s.table[1], s.table[6]};
        reply(s, 0, p);
      });
      return;
    case dxl::kRead: {
      if (broadcast) return;
      Servo* s = find(id);
      if (!s) return;
      if (params.size() != 4) return reply(*s, kInstructionError, {});
      const std::uint16_t address = dxl::read_u16(params);
      const std::uint16_t length = dxl::read_u16(params.subspan(2));
      if (length == 0 || length > 64 || address + length > kTableSize) return reply(*s, kAccessError, {});
      if (answers(*s, dxl::kRead)) reply(*s, 0, std::span(s->table).subspan(address, length));
      return;
    }
    case dxl::kWrite: {
      if (params.size() < 3) {
        if (Servo* s = find(id)) reply(*s, kInstructionError, {});
        return;
      }
      const std::uint16_t address = dxl::read_u16(params);
      for_each_target([&](Servo& s) {
        // The level in force when the packet arrived decides (a write that changes it is still
        // answered as before).
        const bool answer = !broadcast && answers(s, dxl::kWrite);
        const std::uint8_t error = write(s, address, params.subspan(2));
        if (answer) reply(s, error, {});
      });
      return;
    }
    case dxl::kReboot:
      for_each_target([&](Servo& s) {
        s.table[dxl::kHardwareErrorStatus] = 0;
        s.table[dxl::kTorqueEnable] = 0;
        if (!broadcast && answers(s, dxl::kReboot)) reply(s, 0, {});
      });
      return;
    case dxl::kSyncWrite: {
      if (!broadcast || params.size() < 4) return;
      const std::uint16_t address = dxl::read_u16(params);
      const std::uint16_t length = dxl::read_u16(params.subspan(2));
      for (std::size_t at = 4; length > 0 && at + 1 + length <= params.size(); at += 1 + length)
        if (Servo* s = find(params[at])) (void)write(*s, address, params.subspan(at + 1, length));
      return;
    }
    case dxl::kSyncRead: {
      if (!broadcast || params.size() < 5) return;
      const std::uint16_t address = dxl::read_u16(params);
      const std::uint16_t length = dxl::read_u16(params.subspan(2));
      if (length == 0 || length > 64 || address + length > kTableSize) return;
      // Each listed servo answers in the order listed (a real bus serialises them by timing).
      for (std::size_t i = 4; i < params.size(); ++i)
        if (Servo* s = find(params[i]); s && answers(*s, dxl::kSyncRead)) reply(*s, 0, std::span(s->table).subspan(address, length));
      return;
    }
    default:
      if (Servo* s = find(id); s && !broadcast) reply(*s, kInstructionError, {});
      return;
  }
}

std::size_t SimDynamixel::take_replies(std::span<std::uint8_t> out) {
  const std::size_t n = std::min(out.size(), replies_.size());
  std::copy_n(replies_.begin(), n, out.begin());
  replies_.erase(replies_.begin(), replies_.begin() + static_cast<long>(n));
  return n;
}

void SimDynamixel::advance(double dt_s) {
  for (std::size_t i = 0; i < servos_.size(); ++i) {
    Servo& s = servos_[i];
    const std::int32_t profile = read_i32(i, dxl::kProfileVelocity);  // 0.229 rev/min per unit
    s.model.advance(dt_s, s.table[dxl::kTorqueEnable] != 0, read_i32(i, dxl::kGoalPosition), profile * 0.229 / 60.0 * 4096.0);
    const double velocity = s.model.velocity();
    write_i32(s, dxl::kPresentPosition, static_cast<std::int32_t>(std::lround(s.model.position())));
    write_i32(s, kPresentVelocity, static_cast<std::int32_t>(std::lround(velocity / 4096.0 * 60.0 / 0.229)));
    write_u16(s, dxl::kPresentLoad, static_cast<std::uint16_t>(static_cast<std::int16_t>(std::lround(s.model.load() * 1000.0))));
    s.table[kMoving] = std::abs(velocity) > 1 ? 1 : 0;
    const double temperature = s.model.temperature_c();
    s.table[dxl::kPresentTemperature] = static_cast<std::uint8_t>(std::clamp(std::lround(temperature), 0L, 255L));
    if (temperature > s.table[kTemperatureLimit]) {
      s.table[dxl::kHardwareErrorStatus] |= kOverheating;
      if (s.table[kShutdown] & kOverheating) s.table[dxl::kTorqueEnable] = 0;  // shutdown: torque off
    }
  }
}

}  // namespace avar::sim
