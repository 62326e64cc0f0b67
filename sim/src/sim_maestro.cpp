#include "avar/sim/sim_maestro.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::sim {
namespace maestro = firmware_iface::maestro;
namespace {

constexpr double kQuarterPerSecondPerSpeedUnit = 100.0;  // 0.25 µs per 10 ms
constexpr double kQuarterPerSecond2PerAccelUnit = 1250.0;  // 312.5 µs/s²
constexpr std::uint16_t kMaxSpeed = 10000;                // larger values are truncated by the device
constexpr double kServoSubstep_s = 0.001;
constexpr double kMaxPulseUs = maestro::kMaxValue / 4.0;
constexpr std::size_t kLargestPayload = 2 + 2 * maestro::kMaxChannels + 1;  // Set Multiple Targets + CRC

[[noreturn]] void invalid(const std::string& what) { throw std::invalid_argument("simulated Maestro: " + what); }

void validate(const SimMaestroConfig& c) {
  if (c.channel_count != 6 && c.channel_count != 12 && c.channel_count != 18 && c.channel_count != 24)
    invalid("channel count " + std::to_string(c.channel_count) + " is not 6, 12, 18 or 24");
  if (c.device_number > 127) invalid("device number " + std::to_string(c.device_number) + " is above 127");
  if (c.mini_ssc_offset > 254) invalid("Mini SSC offset " + std::to_string(c.mini_ssc_offset) + " is above 254");
  if (!(c.servo.max_speed_us_per_s > 0) || !(c.servo.time_constant_s >= 0) || !(c.servo.deadband_us >= 0))
    invalid("servo parameters need a positive top speed and a non-negative time constant and deadband");
  for (int i = 0; i < c.channel_count; ++i) {
    const SimMaestroChannel& ch = c.channels[static_cast<std::size_t>(i)];
    const std::string name = "channel " + std::to_string(i);
    if (!(ch.min_us > 0) || !(ch.min_us <= ch.max_us) || !(ch.max_us <= kMaxPulseUs))
      invalid(name + " range must satisfy 0 < min_us <= max_us <= 4095.75");
    if (ch.home_us != 0 && !(ch.home_us >= ch.min_us && ch.home_us <= ch.max_us))
      invalid(name + " home must be 0 (off) or inside [min_us, max_us]");
    if (!std::isfinite(ch.neutral_us) || !std::isfinite(ch.range_us) || !std::isfinite(ch.initial_position_us))
      invalid(name + " neutral, range and initial position must be finite");
  }
}

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

SimMaestro::SimMaestro(SimMaestroConfig config) : config_(config) {
  validate(config_);
  channels_.resize(static_cast<std::size_t>(config_.channel_count));
  for (std::size_t i = 0; i < channels_.size(); ++i)
    channels_[i].servo = ServoModel(config_.servo, config_.channels[i].initial_position_us);
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
  set_target(channel, maestro::quarter_us_from_us(ch.neutral_us + (payload_[1] - 127.0) / 127.0 * ch.range_us));
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
      if (channel_ok) set_target(channel, value14(1));
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
      for (int i = 0; i < count; ++i) set_target(first + i, value14(2 + 2 * static_cast<std::size_t>(i)));
      break;
    }
    case maestro::kSetSpeed:
      record({command_, payload_[0], {value14(1)}, form_});
      if (channel_ok) channels_[channel].speed = std::min(value14(1), kMaxSpeed);
      break;
    case maestro::kSetAcceleration:
      record({command_, payload_[0], {value14(1)}, form_});
      if (channel_ok) channels_[channel].acceleration = std::min(value14(1), maestro::kMaxAcceleration);
      break;
    case maestro::kSetPwm:
      record({command_, 0, {value14(0), value14(2)}, form_});
      break;  // the PWM output is not a servo channel: nothing to move
    case maestro::kGetPosition: {
      record({command_, payload_[0], {}, form_});
      const auto q = channel_ok ? static_cast<std::uint16_t>(std::lround(channels_[channel].output_q)) : std::uint16_t{0};
      reply(static_cast<std::uint8_t>(q & 0xFF));
      reply(static_cast<std::uint8_t>(q >> 8));
      break;
    }
    case maestro::kGetMovingState:
      record({command_, 0, {}, form_});
      reply(moving() ? 1 : 0);
      break;
    case maestro::kGetErrors:
      record({command_, 0, {}, form_});
      reply(static_cast<std::uint8_t>(errors_ & 0xFF));
      reply(static_cast<std::uint8_t>(errors_ >> 8));
      errors_ = 0;
      break;
    case maestro::kGoHome:
      record({command_, 0, {}, form_});
      go_home();
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

void SimMaestro::set_target(int channel, std::uint16_t quarter_us) {
  Channel& c = channels_[static_cast<std::size_t>(channel)];
  if (quarter_us == 0) {
    c.target_q = 0;
    c.output_q = 0;
    c.velocity_q = 0;
    return;
  }
  const SimMaestroChannel& limits = config_.channels[static_cast<std::size_t>(channel)];
  c.target_q = static_cast<std::uint16_t>(std::lround(std::clamp<double>(quarter_us, limits.min_us * 4, limits.max_us * 4)));
  // From "no pulses" the first pulse is the target itself: the device does not know where the
  // servo is, so no speed or acceleration limit applies.
  if (c.output_q == 0) c.output_q = c.target_q;
}

void SimMaestro::go_home() {
  for (int i = 0; i < config_.channel_count; ++i) {
    const SimMaestroChannel& ch = config_.channels[static_cast<std::size_t>(i)];
    if (!ch.home_ignore) set_target(i, maestro::quarter_us_from_us(ch.home_us));
  }
}

void SimMaestro::raise(std::uint16_t error_bits) {
  errors_ |= error_bits;
  go_home();  // on any error the Maestro sends its channels to their home positions
}

bool SimMaestro::moving() const {
  return std::any_of(channels_.begin(), channels_.end(), [](const Channel& c) { return c.target_q != 0 && c.output_q != c.target_q; });
}

std::size_t SimMaestro::take_replies(std::span<std::uint8_t> out) {
  const std::size_t n = std::min(out.size(), replies_.size());
  std::copy_n(replies_.begin(), n, out.begin());
  replies_.erase(replies_.begin(), replies_.begin() + static_cast<long>(n));
  return n;
}

void SimMaestro::advance(double dt_s) {
  if (!(dt_s > 0)) return;
  const double steps = std::ceil(dt_s / kServoSubstep_s - 1e-9);
  const int n = std::max(1, static_cast<int>(std::min(steps, 1e9)));
  const double h = dt_s / n;
  for (int i = 0; i < n; ++i) {
    for (Channel& c : channels_) {
      move_output(c, h);
      c.servo.step(h, c.output_q / 4.0);
    }
  }
}

// Moves the output pulse for dt seconds, exactly for any split of the time into steps.
// Without an acceleration limit it moves at the speed limit (or jumps when there is none).
// With one, the motion is a sequence of phases with constant acceleration, worked in the frame
// "toward the target" (d = distance left, u = velocity toward the target):
//   moving away  -> brake at a until u = 0;
//   u² >= 2ad    -> brake to stop on the target (at a when the motion arrived here on its own,
//                   harder only when a new target lies inside the braking distance);
//   u < v_max    -> speed up at a until v_max or until u² = 2ad, whichever comes first;
//   otherwise    -> cruise at v_max until u² = 2ad.
void SimMaestro::move_output(Channel& c, double dt_s) {
  if (c.target_q == 0 || c.output_q == c.target_q) {
    c.velocity_q = 0;
    return;
  }
  const double v_max = c.speed ? c.speed * kQuarterPerSecondPerSpeedUnit : std::numeric_limits<double>::infinity();
  if (c.acceleration == 0) {
    const double distance = c.target_q - c.output_q;
    const double direction = distance > 0 ? 1.0 : -1.0;
    const double step = v_max * dt_s;
    if (std::abs(distance) <= step) {
      c.output_q = c.target_q;
      c.velocity_q = 0;
    } else {
      c.output_q += direction * step;
      c.velocity_q = direction * v_max;
    }
    return;
  }
  const double a = c.acceleration * kQuarterPerSecond2PerAccelUnit;
  constexpr double kSnap = 1e-9;  // quarter-µs: closer than this is on the target
  double t = dt_s;
  bool at_braking_point = false;  // the previous phase ended where braking must begin
  // Each phase ends at an event that leads to a later kind of phase, so four suffice; the
  // bound only guards against a floating-point stall. Phase ends set the velocity exactly (0,
  // v_max) so that rounding cannot leave a sliver of a phase for the next step.
  for (int phase = 0; phase < 8 && t > 0; ++phase) {
    const double offset = c.target_q - c.output_q;
    const double s = offset > 0 ? 1.0 : -1.0;
    const double d = std::abs(offset);
    const double u = std::min(c.velocity_q * s, v_max);  // a lowered speed limit applies at once
    double accel = 0;
    double duration = t;
    double u_end = 0;
    if (u < 0) {
      const double to_rest = -u / a;
      accel = a;
      duration = std::min(t, to_rest);
      u_end = duration == to_rest ? 0.0 : u + a * duration;
    } else if (u > 0 && (at_braking_point || u * u >= 2 * a * d)) {
      const double stop_time = 2 * d / u;
      if (stop_time <= t) {
        c.output_q = c.target_q;
        c.velocity_q = 0;
        return;
      }
      accel = -u / stop_time;
      u_end = u + accel * t;
    } else if (u < v_max) {
      const double to_v_max = (v_max - u) / a;
      const double to_braking = (std::sqrt(a * d + u * u / 2) - u) / a;
      accel = a;
      duration = std::min({t, to_v_max, to_braking});
      at_braking_point = duration == to_braking;
      u_end = duration == to_v_max ? v_max : u + a * duration;
    } else {
      const double to_braking = std::max(0.0, (d - u * u / (2 * a)) / u);
      duration = std::min(t, to_braking);
      at_braking_point = duration == to_braking;
      u_end = u;
    }
    const double moved = u * duration + accel * duration * duration / 2;
    t -= duration;
    if (std::abs(d - moved) < kSnap) {
      c.output_q = c.target_q;
      c.velocity_q = 0;
      return;
    }
    c.output_q += s * moved;
    c.velocity_q = s * u_end;
  }
}

}  // namespace avar::sim
