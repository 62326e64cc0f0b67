#include "avar/sim/sim_maestro.hpp"

#include <algorithm>
#include <cmath>

#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::sim {
namespace maestro = firmware_iface::maestro;
namespace {

constexpr std::size_t kLargestPayload = 2 + 2 * maestro::kMaxChannels + 1;  // Set Multiple Targets + CRC

/// Commands the device knows, and how many data bytes follow each (Set Multiple Targets: at
/// least the count byte; the rest depends on it).
bool known_command(std::uint8_t command, int channel_count) {
  switch (command) {
    case maestro::kSetTarget:
    case maestro::kSetSpeed:
    case maestro::kSetAcceleration:
    case maestro::kGetPosition:
    case maestro::kGetMovingState:
    case maestro::kGetErrors:
    case maestro::kGoHome:
    case maestro::kStopScript:
    case maestro::kRestartScript:
    case maestro::kRestartScriptWithParameter:
    case maestro::kGetScriptStatus: return true;
    case maestro::kSetMultipleTargets:
    case maestro::kSetPwm: return channel_count > 6;  // Mini Maestro only
    default: return false;
  }
}

}  // namespace

SimMaestro::SimMaestro(SimMaestroConfig config) : config_(config), servos_(config_) {
  packet_.reserve(kLargestPayload + 3);
  payload_.reserve(kLargestPayload);
}

std::uint16_t SimMaestro::value14(std::size_t at) const {
  return static_cast<std::uint16_t>(payload_[at] | (payload_[at + 1] << 7));
}

std::size_t SimMaestro::payload_size() const {
  switch (command_) {
    case maestro::kSetTarget:
    case maestro::kSetSpeed:
    case maestro::kSetAcceleration:
    case maestro::kRestartScriptWithParameter: return 3;
    case maestro::kSetPwm: return 4;
    case maestro::kGetPosition:
    case maestro::kRestartScript: return 1;
    case maestro::kSetMultipleTargets: return payload_.empty() ? 1 : 2 + 2 * static_cast<std::size_t>(payload_[0]);
    default: return 0;
  }
}

void SimMaestro::receive(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) {
    ++bytes_received_;
    take(b);
  }
}

void SimMaestro::take(std::uint8_t b) {
  if (config_.baud_detect && !baud_locked_) {
    // Until the 0xAA has been measured the UART cannot frame bytes: everything else is noise.
    if (b != maestro::kPololuStart) return;
    baud_locked_ = true;
    begin_packet(b);
    lone_baud_byte_ = true;
    return;
  }
  if (state_ == State::mini_ssc && b != maestro::kMiniSscStart) {
    take_mini_ssc(b);  // Mini SSC data bytes may have the top bit set (0x00..0xFE)
    return;
  }
  if (b & 0x80) {
    const bool unfinished = state_ != State::idle && state_ != State::skip && !lone_baud_byte_;
    if (unfinished) raise(maestro::kSerialProtocolError);
    begin_packet(b);
    return;
  }
  switch (state_) {
    case State::idle:
    case State::skip: return;  // a data byte outside any packet of ours
    case State::pololu_device:
      packet_.push_back(b);
      lone_baud_byte_ = false;
      state_ = b == config_.device_number ? State::pololu_command : State::skip;
      return;
    case State::pololu_command:
      packet_.push_back(b);
      start_command(static_cast<std::uint8_t>(b | 0x80));
      return;
    case State::payload: take_payload(b); return;
    case State::mini_ssc: return;  // handled above
  }
}

void SimMaestro::begin_packet(std::uint8_t first_byte) {
  packet_.assign(1, first_byte);
  payload_.clear();
  lone_baud_byte_ = false;
  if (first_byte == maestro::kPololuStart) {
    form_ = MaestroCommand::Form::pololu;
    state_ = State::pololu_device;
  } else if (first_byte == maestro::kMiniSscStart) {
    form_ = MaestroCommand::Form::mini_ssc;
    state_ = State::mini_ssc;
  } else {
    form_ = MaestroCommand::Form::compact;
    start_command(first_byte);
  }
}

void SimMaestro::start_command(std::uint8_t command_byte) {
  if (!known_command(command_byte, config_.channel_count)) {
    state_ = State::idle;
    raise(maestro::kSerialProtocolError);
    return;
  }
  command_ = command_byte;
  state_ = State::payload;
  if (payload_size() == 0 && !config_.crc) finish_packet();
}

void SimMaestro::take_payload(std::uint8_t b) {
  packet_.push_back(b);
  payload_.push_back(b);
  if (command_ == maestro::kSetMultipleTargets && payload_.size() == 1 && (b == 0 || b > config_.channel_count)) {
    state_ = State::idle;
    raise(maestro::kSerialProtocolError);
    return;
  }
  if (payload_.size() == payload_size() + (config_.crc ? 1u : 0u)) finish_packet();
}

void SimMaestro::take_mini_ssc(std::uint8_t b) {
  payload_.push_back(b);
  if (payload_.size() < 2) return;
  state_ = State::idle;
  // Addresses outside this device's channels belong to other devices on the line.
  if (payload_[0] < config_.mini_ssc_offset) return;
  const int channel = payload_[0] - config_.mini_ssc_offset;
  if (channel >= config_.channel_count) return;
  record({maestro::kMiniSscStart, static_cast<std::uint8_t>(channel), {payload_[1]}, form_});
  const SimMaestroChannel& ch = config_.channels[static_cast<std::size_t>(channel)];
  servos_.set_target(channel, maestro::quarter_us_from_us(ch.neutral_us + (payload_[1] - 127.0) / 127.0 * ch.range_us));
}

void SimMaestro::finish_packet() {
  state_ = State::idle;
  if (config_.crc) {
    const std::uint8_t expected = maestro::crc7(std::span(packet_.data(), packet_.size() - 1));
    if (packet_.back() != expected) {
      raise(maestro::kSerialCrcError);
      return;
    }
    payload_.pop_back();
  }
  execute();
}

void SimMaestro::record(MaestroCommand command) {
  if (config_.log_limit == 0) return;
  if (log_.size() == config_.log_limit) log_.pop_front();
  log_.push_back(std::move(command));
}

void SimMaestro::execute() {
  const int channel = payload_.empty() ? 0 : payload_[0];
  const bool channel_ok = channel < config_.channel_count;
  switch (command_) {
    case maestro::kSetTarget:
      record({command_, payload_[0], {value14(1)}, form_});
      if (channel_ok) servos_.set_target(channel, value14(1));
      break;
    case maestro::kSetMultipleTargets: {
      const int count = payload_[0];
      const int first = payload_[1];
      MaestroCommand logged{command_, payload_[1], {}, form_};
      for (int i = 0; i < count; ++i) logged.values.push_back(value14(2 + 2 * static_cast<std::size_t>(i)));
      record(std::move(logged));
      if (first + count > config_.channel_count) {
        raise(maestro::kSerialProtocolError);
        break;
      }
      for (int i = 0; i < count; ++i) servos_.set_target(first + i, value14(2 + 2 * static_cast<std::size_t>(i)));
      break;
    }
    case maestro::kSetSpeed:
      record({command_, payload_[0], {value14(1)}, form_});
      if (channel_ok) servos_.set_speed(channel, value14(1));
      break;
    case maestro::kSetAcceleration:
      record({command_, payload_[0], {value14(1)}, form_});
      if (channel_ok) servos_.set_acceleration(channel, value14(1));
      break;
    case maestro::kSetPwm:
      record({command_, 0, {value14(0), value14(2)}, form_});
      break;  // the PWM output is not a servo channel: nothing to move
    case maestro::kGetPosition: {
      record({command_, payload_[0], {}, form_});
      const auto q = channel_ok ? static_cast<std::uint16_t>(std::lround(servos_.output_pulse(channel))) : std::uint16_t{0};
      reply_u16(q);
      break;
    }
    case maestro::kGetMovingState:
      record({command_, 0, {}, form_});
      reply(moving() ? 1 : 0);
      break;
    case maestro::kGetErrors:
      record({command_, 0, {}, form_});
      reply_u16(servos_.errors());
      servos_.clear_errors();
      break;
    case maestro::kGoHome:
      record({command_, 0, {}, form_});
      servos_.go_home();
      break;
    case maestro::kRestartScript:
      record({command_, 0, {payload_[0]}, form_});
      break;  // no script is loaded: nothing runs
    case maestro::kRestartScriptWithParameter:
      record({command_, 0, {payload_[0], value14(1)}, form_});
      break;
    case maestro::kGetScriptStatus:
      record({command_, 0, {}, form_});
      reply(0x01);  // 0x01: the script is stopped (none is loaded)
      break;
    default:  // Stop Script
      record({command_, 0, {}, form_});
      break;
  }
}

std::size_t SimMaestro::take_replies(std::span<std::uint8_t> out) {
  const std::size_t n = std::min(out.size(), replies_.size());
  std::copy_n(replies_.begin(), n, out.begin());
  replies_.erase(replies_.begin(), replies_.begin() + static_cast<long>(n));
  return n;
}

void SimMaestro::advance(double dt_s) { servos_.advance(dt_s); }

}  // namespace avar::sim
