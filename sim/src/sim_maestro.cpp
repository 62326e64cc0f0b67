#include "avar/sim/sim_maestro.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::sim {
namespace maestro = firmware_iface::maestro;
namespace {

constexpr double kQuarterPerSpeedUnit = 100.0;     // 0.25 µs per 10 ms = 100 quarter-µs per second
constexpr double kQuarterPerAccelUnit = 1250.0;    // 312.5 µs/s² = 1250 quarter-µs/s²
constexpr std::size_t kUnknownSize = std::numeric_limits<std::size_t>::max();

}  // namespace

SimMaestro::SimMaestro(SimMaestroConfig config) : config_(config), channels_(static_cast<std::size_t>(config.channel_count)) {
  for (std::size_t i = 0; i < channels_.size(); ++i)
    channels_[i].servo = ServoModel(config_.servo, config_.channels[i].initial_position_us);
  packet_.reserve(64);
  payload_.reserve(64);
}

std::uint16_t SimMaestro::value14(std::size_t at) const {
  return static_cast<std::uint16_t>(payload_[at] | (payload_[at + 1] << 7));
}

std::size_t SimMaestro::payload_size() const {
  switch (command_) {
    case maestro::kSetTarget:
    case maestro::kSetSpeed:
    case maestro::kSetAcceleration: return 3;
    case maestro::kSetPwm: return 4;
    case maestro::kGetPosition: return 1;
    case maestro::kSetMultipleTargets: return payload_.empty() ? kUnknownSize : 2 + 2 * static_cast<std::size_t>(payload_[0]);
    case 0xA7: return 1;  // Restart Script at Subroutine
    case 0xA8: return 3;  // Restart Script at Subroutine with Parameter
    default: return 0;    // Get Moving State, Get Errors, Go Home, Stop Script, Get Script Status
  }
}

void SimMaestro::start_command(std::uint8_t command_byte) {
  switch (command_byte) {
    case maestro::kSetTarget:
    case maestro::kSetSpeed:
    case maestro::kSetAcceleration:
    case maestro::kSetPwm:
    case maestro::kGetPosition:
    case maestro::kGetMovingState:
    case maestro::kGetErrors:
    case maestro::kGoHome:
    case 0xA4:
    case 0xA7:
    case 0xA8:
    case 0xAE: break;
    case maestro::kSetMultipleTargets:
      if (config_.channel_count > 6) break;
      [[fallthrough]];  // the Micro Maestro does not know this command
    default:
      state_ = State::idle;
      raise(maestro::kSerialProtocolError);
      return;
  }
  command_ = command_byte;
  payload_.clear();
  state_ = State::payload;
  if (payload_size() == 0 && !config_.crc) finish_packet();
}

void SimMaestro::receive(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) {
    ++bytes_received_;
    if (config_.baud_detect && !baud_locked_) {
      baud_locked_ = b == maestro::kPololuStart;  // everything before the 0xAA is line noise
      continue;
    }
    if (state_ == State::mini_ssc && b != maestro::kMiniSscStart) {
      // Mini SSC data bytes may have the top bit set (0x00..0xFE).
      payload_.push_back(b);
      if (payload_.size() == 2) {
        const int channel = payload_[0] - config_.mini_ssc_offset;
        if (payload_[0] >= config_.mini_ssc_offset && channel < config_.channel_count) {
          // 127 is the neutral 1500 µs; 0 and 254 are neutral -/+ the 8-bit range 476.25 µs.
          const double us = 1500.0 + (payload_[1] - 127.0) / 127.0 * 476.25;
          set_target(channel, maestro::quarter_us_from_us(us));
          if (config_.log_limit) {
            log_.push_back({maestro::kMiniSscStart, static_cast<std::uint8_t>(channel), {payload_[1]}});
            if (log_.size() > config_.log_limit) log_.pop_front();
          }
        }
        state_ = State::idle;
      }
      continue;
    }
    if (b & 0x80) {
      if (state_ != State::idle) raise(maestro::kSerialProtocolError);  // a packet was interrupted
      packet_.assign(1, b);
      payload_.clear();
      for_us_ = true;
      if (b == maestro::kPololuStart)
        state_ = State::pololu_device;
      else if (b == maestro::kMiniSscStart)
        state_ = State::mini_ssc;
      else
        start_command(b);
      continue;
    }
    if (state_ == State::idle) continue;  // a stray data byte belongs to no packet
    packet_.push_back(b);
    switch (state_) {
      case State::pololu_device:
        for_us_ = b == config_.device_number;
        state_ = State::pololu_command;
        break;
      case State::pololu_command: start_command(static_cast<std::uint8_t>(b | 0x80)); break;
      case State::payload: {
        payload_.push_back(b);
        const std::size_t need = payload_size();
        if (command_ == maestro::kSetMultipleTargets && payload_.size() == 1 && (b == 0 || b > config_.channel_count)) {
          state_ = State::idle;
          if (for_us_) raise(maestro::kSerialProtocolError);
          break;
        }
        if (need != kUnknownSize && payload_.size() >= need + (config_.crc ? 1 : 0)) finish_packet();
        break;
      }
      default: break;
    }
  }
}

void SimMaestro::finish_packet() {
  state_ = State::idle;
  if (config_.crc) {
    const std::uint8_t expected = maestro::crc7(std::span(packet_.data(), packet_.size() - 1));
    if (packet_.back() != expected) {
      // Packets for other devices are not checked (assumption recorded in the protocol notes).
      if (for_us_) raise(maestro::kSerialCrcError);
      return;
    }
    payload_.pop_back();
  }
  if (for_us_) execute();
}

void SimMaestro::execute() {
  if (config_.log_limit) {
    MaestroCommand logged{command_, payload_.empty() ? std::uint8_t{0} : payload_[0], {}};
    if (command_ == maestro::kSetMultipleTargets) {
      logged.channel = payload_[1];
      for (std::size_t i = 2; i + 1 < payload_.size(); i += 2) logged.values.push_back(value14(i));
    } else if (payload_.size() >= 3) {
      logged.values.push_back(value14(1));
    }
    log_.push_back(std::move(logged));
    if (log_.size() > config_.log_limit) log_.pop_front();
  }
  const int channel = payload_.empty() ? 0 : payload_[0];
  const bool channel_ok = channel < config_.channel_count;
  switch (command_) {
    case maestro::kSetTarget:
      if (channel_ok) set_target(channel, value14(1));
      break;
    case maestro::kSetMultipleTargets: {
      const int count = payload_[0];
      const int first = payload_[1];
      if (first + count > config_.channel_count) {
        raise(maestro::kSerialProtocolError);
        break;
      }
      for (int i = 0; i < count; ++i) set_target(first + i, value14(2 + 2 * static_cast<std::size_t>(i)));
      break;
    }
    case maestro::kSetSpeed:
      if (channel_ok) channels_[channel].speed = std::min<std::uint16_t>(value14(1), 10000);  // larger values truncate
      break;
    case maestro::kSetAcceleration:
      if (channel_ok) channels_[channel].acceleration = std::min<std::uint16_t>(value14(1), 255);
      break;
    case maestro::kGetPosition: {
      const auto q = channel_ok ? static_cast<std::uint16_t>(std::lround(channels_[channel].output_q)) : std::uint16_t{0};
      reply({static_cast<std::uint8_t>(q & 0xFF), static_cast<std::uint8_t>(q >> 8)});
      break;
    }
    case maestro::kGetMovingState: {
      bool moving = false;
      for (const Channel& c : channels_) moving = moving || (c.target_q != 0 && c.output_q != c.target_q);
      reply({static_cast<std::uint8_t>(moving ? 1 : 0)});
      break;
    }
    case maestro::kGetErrors:
      reply({static_cast<std::uint8_t>(errors_ & 0xFF), static_cast<std::uint8_t>(errors_ >> 8)});
      errors_ = 0;
      break;
    case maestro::kGoHome:
      for (int i = 0; i < config_.channel_count; ++i)
        set_target(i, maestro::quarter_us_from_us(config_.channels[static_cast<std::size_t>(i)].home_us));
      break;
    case 0xAE: reply({0x01}); break;  // Get Script Status: no script running
    default: break;                   // Set PWM and script control: no effect on servos
  }
}

void SimMaestro::set_target(int channel, std::uint16_t quarter_us) {
  Channel& c = channels_[static_cast<std::size_t>(channel)];
  if (quarter_us == 0) {
    c.target_q = 0;
    c.output_q = 0;
    c.velocity_q = 0;
    return;
  }
  const SimMaestroChannel& limits = config_.channels[static_cast<std::size_t>(channel)];
  c.target_q = static_cast<std::uint16_t>(std::clamp<double>(quarter_us, limits.min_us * 4, limits.max_us * 4));
  if (c.output_q == 0) c.output_q = c.target_q;  // pulses start at the target: no limit applies
}

void SimMaestro::raise(std::uint16_t error_bits) {
  errors_ |= error_bits;
  // On any error the Maestro sends every channel to its home (error) position.
  for (int i = 0; i < config_.channel_count; ++i)
    set_target(i, maestro::quarter_us_from_us(config_.channels[static_cast<std::size_t>(i)].home_us));
}

void SimMaestro::reply(std::initializer_list<std::uint8_t> bytes) { replies_.insert(replies_.end(), bytes); }

std::size_t SimMaestro::take_replies(std::span<std::uint8_t> out) {
  const std::size_t n = std::min(out.size(), replies_.size());
  std::copy_n(replies_.begin(), n, out.begin());
  replies_.erase(replies_.begin(), replies_.begin() + static_cast<long>(n));
  return n;
}

void SimMaestro::advance(double dt_s) {
  for (Channel& c : channels_) {
    if (c.target_q != 0 && c.output_q != c.target_q) {
      const double distance = c.target_q - c.output_q;
      const double direction = distance > 0 ? 1.0 : -1.0;
      const double v_max = c.speed ? c.speed * kQuarterPerSpeedUnit : std::numeric_limits<double>::infinity();
      double step;
      if (c.acceleration == 0) {
        step = v_max * dt_s;
        c.velocity_q = 0;
      } else {
        // Trapezoidal profile: speed up by the acceleration, never faster than the speed
        // limit, and slow down in time to stop at the target.
        const double a = c.acceleration * kQuarterPerAccelUnit;
        const double along = std::max(0.0, c.velocity_q * direction);
        const double v = std::min({along + a * dt_s, v_max, std::sqrt(2.0 * a * std::abs(distance))});
        c.velocity_q = direction * v;
        step = v * dt_s;
      }
      c.output_q = std::abs(distance) <= step ? c.target_q : c.output_q + direction * step;
      if (c.output_q == c.target_q) c.velocity_q = 0;
    }
    c.servo.step(dt_s, c.output_q / 4.0);
  }
}

}  // namespace avar::sim
