#include "avar/sim/sim_feetech.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "avar/firmware_iface/wire_time.hpp"
#include "avar/sim/reply_queue.hpp"

namespace avar::sim {
namespace ft = firmware_iface::feetech;
namespace {

constexpr std::uint8_t kMaxTorque = 16;
constexpr std::uint8_t kLedAlarmCondition = 20;
constexpr std::uint8_t kTorqueLimitSts = 48;
constexpr std::uint8_t kRecentre = 128;  // Torque Enable value: "here is the centre"
constexpr int kBaudTable[] = {1000000, 500000, 250000, 128000, 115200, 76800, 57600, 38400, 19200, 14400, 9600, 4800};

bool read_only(std::size_t address) { return address < ft::kId || address >= ft::kPresentPosition; }

}  // namespace

int SimFeetech::baud_code(int baud) noexcept {
  for (int i = 0; i < static_cast<int>(std::size(kBaudTable)); ++i)
    if (kBaudTable[i] == baud) return i;
  return -1;
}

SimFeetech::SimFeetech(SimFeetechConfig config) : config_(std::move(config)) {
  const int code = baud_code(config_.baud);
  if (code < 0) throw std::invalid_argument("a Feetech servo cannot run at " + std::to_string(config_.baud) + " baud");
  const bool sts = config_.series == ft::Series::sts;
  const int resolution = ft::position_resolution(config_.series);
  for (const SimFeetechServo& spec : config_.servos) {
    if (spec.id > ft::kMaxId) throw std::invalid_argument("Feetech ID " + std::to_string(spec.id) + " is above 253");
    for (const Servo& other : servos_)
      if (other.spec.id == spec.id) throw std::invalid_argument("Feetech ID " + std::to_string(spec.id) + " is used twice");
    Servo s;
    s.spec = spec;
    const double initial = spec.initial_position < 0 ? resolution / 2 : spec.initial_position;
    s.model = SmartServoModel({spec.max_speed_steps_per_s, spec.max_acceleration_steps_per_s2, spec.time_constant_s,
                               spec.deadband_steps, spec.ambient_c, spec.heating_c_per_s_at_full_load, spec.cooling_per_s},
                              initial);
    s.model.set_external_load(spec.external_load);
    s.table[0] = 3, s.table[1] = 10;  // firmware 3.10
    put_word(s, ft::kModelNumber, sts ? 777 : 1284);  // STS3215 / SCS0009
    s.table[ft::kId] = spec.id;
    s.table[ft::kBaudRate] = static_cast<std::uint8_t>(code);
    s.table[ft::kReturnDelay] = 0;
    s.table[ft::kResponseLevel] = 1;
    put_word(s, ft::kMinPositionLimit, 0);
    put_word(s, ft::kMaxPositionLimit, static_cast<std::uint16_t>(resolution - 1));
    s.table[ft::kMaxTemperature] = spec.max_temperature_c;
    put_word(s, kMaxTorque, 1000);
    s.table[ft::kUnloadingCondition] = ft::kErrorOverheat | ft::kErrorOverCurrent | ft::kErrorOverload;
    s.table[kLedAlarmCondition] = s.table[ft::kUnloadingCondition] | ft::kErrorAngleSensor | ft::kErrorVoltage;
    put_word(s, ft::kGoalPosition, static_cast<std::uint16_t>(std::lround(initial)));
    if (sts) put_word(s, kTorqueLimitSts, 1000);
    s.table[sts ? ft::kLockSts : ft::kLockScs] = 1;
    servos_.push_back(std::move(s));
  }
  for (Servo& s : servos_) step(s, 0);  // present-value registers
  input_.reserve(1024);
}

double SimFeetech::position(std::size_t servo) const { return servos_[servo].model.position(); }

double SimFeetech::wire_time(std::size_t bytes) const { return firmware_iface::wire_seconds(bytes, config_.baud); }

std::uint16_t SimFeetech::read_word(std::size_t servo, std::uint8_t address) const {
  return ft::get_word(config_.series, std::span(servos_[servo].table).subspan(address, 2));
}

void SimFeetech::put_word(Servo& s, std::uint8_t address, std::uint16_t v) {
  ft::put_word(config_.series, std::span<std::uint8_t, 2>(&s.table[address], 2), v);
}

SimFeetech::Servo* SimFeetech::find(std::uint8_t id) {
  for (Servo& s : servos_)
    if (s.table[ft::kId] == id) return &s;
  return nullptr;
}

void SimFeetech::reply(const Servo& s, std::uint8_t error, std::span<const std::uint8_t> params) {
  std::array<std::uint8_t, ft::kMaxPacketSize> packet{};
  const auto status = static_cast<std::uint8_t>(error | s.table[ft::kStatus]);
  const std::size_t n = ft::encode_packet(packet, s.table[ft::kId], status, params);
  replies_.insert(replies_.end(), packet.begin(), packet.begin() + static_cast<long>(n));
}

std::uint8_t SimFeetech::write(Servo& s, std::uint8_t address, std::span<const std::uint8_t> data) {
  if (data.empty() || address + data.size() > kTableSize) return ft::kErrorRange;
  for (std::size_t i = 0; i < data.size(); ++i)
    if (read_only(address + i)) return ft::kErrorRange;
  const auto covers = [&](std::uint8_t reg, std::size_t size) { return address <= reg && reg + size <= address + data.size(); };
  if (covers(ft::kGoalPosition, 2)) {
    const std::uint16_t raw = ft::get_word(config_.series, data.subspan(ft::kGoalPosition - address, 2));
    const int goal = ft::position_from_word(config_.series, raw);
    const int lo = ft::get_word(config_.series, std::span(s.table).subspan(ft::kMinPositionLimit, 2));
    const int hi = ft::get_word(config_.series, std::span(s.table).subspan(ft::kMaxPositionLimit, 2));
    if (!(lo == 0 && hi == 0) && (goal < lo || goal > hi)) return ft::kErrorRange;
  }
  std::uint8_t torque = 0;
  if (covers(ft::kTorqueEnable, 1)) {
    torque = data[ft::kTorqueEnable - address];
    if (torque > 2 && torque != kRecentre) return ft::kErrorRange;
  }
  if (covers(ft::kBaudRate, 1) && data[ft::kBaudRate - address] >= std::size(kBaudTable)) return ft::kErrorRange;
  if (covers(ft::kResponseLevel, 1) && data[ft::kResponseLevel - address] > 1) return ft::kErrorRange;
  const std::uint8_t previous_torque = s.table[ft::kTorqueEnable];
  std::copy(data.begin(), data.end(), s.table.begin() + address);
  if (covers(ft::kTorqueEnable, 1) && torque == kRecentre) {
    // The present position becomes the centre; torque stays as it was.
    s.table[ft::kTorqueEnable] = previous_torque;
    const double centre = ft::position_resolution(config_.series) / 2;
    s.model.set_position(centre);
    put_word(s, ft::kGoalPosition, static_cast<std::uint16_t>(centre));
    step(s, 0);
  }
  return 0;
}

void SimFeetech::receive(std::span<const std::uint8_t> bytes) {
  bytes_received_ += bytes.size();
  input_.insert(input_.end(), bytes.begin(), bytes.end());
  std::size_t at = 0;
  for (;;) {
    ft::Packet packet;
    std::size_t used = 0;
    const ft::DecodeResult r = ft::decode_packet(std::span(input_).subspan(at), &packet, &used);
    at += used;
    if (r == ft::DecodeResult::need_more) break;
    if (r == ft::DecodeResult::bad_checksum) {
      ++checksum_errors_;
      // The addressed servo says so (never to a broadcast).
      if (Servo* s = find(input_[at - used + 2])) reply(*s, ft::kErrorChecksum, {});
      continue;
    }
    if (r != ft::DecodeResult::ok) continue;
    if (config_.log_limit) {
      log_.push_back({packet.id, packet.code, std::vector<std::uint8_t>(packet.params.begin(), packet.params.end())});
      if (log_.size() > config_.log_limit) log_.pop_front();
    }
    handle(packet.id, packet.code, packet.params);
  }
  input_.erase(input_.begin(), input_.begin() + static_cast<long>(at));
}

void SimFeetech::handle(std::uint8_t id, std::uint8_t instruction, std::span<const std::uint8_t> params) {
  const bool broadcast = id == ft::kBroadcastId;
  Servo* target = broadcast ? nullptr : find(id);
  if (!broadcast && !target) return;  // nobody on the bus has this ID
  // Response Level 1 answers every non-broadcast instruction; 0 only Read and Ping.
  const auto answers = [&](const Servo& s) { return !broadcast && s.table[ft::kResponseLevel] >= 1; };
  const auto for_each_target = [&](auto&& f) {
    if (broadcast) {
      for (Servo& s : servos_) f(s);
    } else {
      f(*target);
    }
  };
  switch (instruction) {
    case ft::kPing:
      if (!broadcast) reply(*target, 0, {});
      return;
    case ft::kRead: {
      if (broadcast) return;
      if (params.size() != 2) return reply(*target, ft::kErrorInstruction, {});
      const std::size_t address = params[0], length = params[1];
      if (length == 0 || address + length > kTableSize) return reply(*target, ft::kErrorRange, {});
      return reply(*target, 0, std::span(target->table).subspan(address, length));
    }
    case ft::kWrite:
    case ft::kRegWrite:
      if (params.size() < 2) {
        if (!broadcast) reply(*target, ft::kErrorInstruction, {});
        return;
      }
      for_each_target([&](Servo& s) {
        const bool answer = answers(s);  // the level in force when the packet arrived
        std::uint8_t error = 0;
        if (instruction == ft::kWrite) {
          error = write(s, params[0], params.subspan(1));
        } else {
          s.pending = true;
          s.pending_address = params[0];
          s.pending_data.assign(params.begin() + 1, params.end());
        }
        if (answer) reply(s, error, {});
      });
      return;
    case ft::kAction:
      for_each_target([&](Servo& s) {
        const bool answer = answers(s);
        std::uint8_t error = 0;
        if (s.pending) error = write(s, s.pending_address, s.pending_data);
        s.pending = false;
        if (answer) reply(s, error, {});
      });
      return;
    case ft::kSyncWrite: {
      if (!broadcast || params.size() < 2) return;
      const std::size_t address = params[0], length = params[1];
      for (std::size_t at = 2; length > 0 && at + 1 + length <= params.size(); at += 1 + length)
        if (Servo* s = find(params[at])) (void)write(*s, static_cast<std::uint8_t>(address), params.subspan(at + 1, length));
      return;
    }
    case ft::kSyncRead: {
      if (!broadcast || params.size() < 3) return;
      const std::size_t address = params[0], length = params[1];
      if (length == 0 || address + length > kTableSize) return;
      // Each listed servo answers in the order listed (a real bus serialises them by timing).
      for (std::size_t i = 2; i < params.size(); ++i)
        if (Servo* s = find(params[i])) reply(*s, 0, std::span(s->table).subspan(address, length));
      return;
    }
    default:
      if (!broadcast) reply(*target, ft::kErrorInstruction, {});
      return;
  }
}

std::size_t SimFeetech::take_replies(std::span<std::uint8_t> out) {
  return take_from(replies_, out);
}

void SimFeetech::advance(double dt_s) {
  if (!(dt_s > 0)) return;
  // Protection acts within a step of the model.
  const int steps = static_cast<int>(std::ceil(dt_s / SmartServoModel::kMaxStep_s));
  for (Servo& s : servos_)
    for (int i = 0; i < steps; ++i) step(s, dt_s / steps);
}

void SimFeetech::step(Servo& s, double dt_s) {
  const std::size_t i = static_cast<std::size_t>(&s - servos_.data());
  const double before = s.model.position();
  const double goal = ft::position_from_word(config_.series, read_word(i, ft::kGoalPosition));
  const int speed_reg = std::abs(ft::from_sign_magnitude(read_word(i, ft::kGoalSpeed), ft::kSpeedSignBit));
  s.model.advance(dt_s, s.table[ft::kTorqueEnable] == 1, goal, speed_reg, s.table[ft::kAcceleration] * 100.0);
  const double temperature = s.model.temperature_c();
  // Overheat holds until the servo has cooled 5 °C below its limit.
  std::uint8_t status = s.table[ft::kStatus] & ft::kErrorOverheat;
  if (temperature > s.table[ft::kMaxTemperature]) status |= ft::kErrorOverheat;
  if (temperature < s.table[ft::kMaxTemperature] - 5.0) status &= static_cast<std::uint8_t>(~ft::kErrorOverheat);
  if (std::abs(s.model.load()) >= 0.99) status |= ft::kErrorOverload;
  s.table[ft::kStatus] = status;
  if (status & s.table[ft::kUnloadingCondition]) s.table[ft::kTorqueEnable] = 0;  // protection: torque off
  const double position = s.model.position();
  const long steps = std::lround(position);
  put_word(s, ft::kPresentPosition, ft::position_word(config_.series, steps));
  put_word(s, ft::kPresentSpeed, ft::to_sign_magnitude(static_cast<int>(std::lround(s.model.velocity())), ft::kSpeedSignBit));
  put_word(s, ft::kPresentLoad, ft::to_sign_magnitude(static_cast<int>(std::lround(s.model.load() * 1000)), ft::kLoadSignBit));
  s.table[ft::kPresentVoltage] = s.spec.voltage_decivolts;
  s.table[ft::kPresentTemperature] = static_cast<std::uint8_t>(std::clamp(std::lround(temperature), 0L, 255L));
  s.table[ft::kMoving] = std::abs(position - before) > 0 && std::abs(s.model.velocity()) > 1 ? 1 : 0;
}

}  // namespace avar::sim
