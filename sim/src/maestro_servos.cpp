#include "avar/sim/maestro_servos.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "avar/firmware_iface/maestro_codec.hpp"

namespace avar::sim {
namespace maestro = firmware_iface::maestro;
namespace {

constexpr double kQuarterPerSecondPerSpeedUnit = 100.0;    // 0.25 µs per 10 ms
constexpr double kQuarterPerSecond2PerAccelUnit = 1250.0;  // 312.5 µs/s²
constexpr std::uint16_t kMaxSpeed = 10000;                 // larger values are truncated by the device
constexpr double kServoSubstep_s = 0.001;
constexpr double kMaxPulseUs = maestro::kMaxValue / 4.0;

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

}  // namespace

MaestroServos::MaestroServos(const SimMaestroConfig& config) : settings_(config.channels) {
  validate(config);
  channels_.resize(static_cast<std::size_t>(config.channel_count));
  for (std::size_t i = 0; i < channels_.size(); ++i)
    channels_[i].servo = ServoModel(config.servo, settings_[i].initial_position_us);
}

void MaestroServos::set_speed(int channel, std::uint16_t speed) {
  channels_[static_cast<std::size_t>(channel)].speed = std::min(speed, kMaxSpeed);
}

void MaestroServos::set_acceleration(int channel, std::uint16_t acceleration) {
  channels_[static_cast<std::size_t>(channel)].acceleration = std::min(acceleration, maestro::kMaxAcceleration);
}

void MaestroServos::set_target(int channel, std::uint16_t quarter_us) {
  Channel& c = channels_[static_cast<std::size_t>(channel)];
  if (quarter_us == 0) {
    c.target_q = 0;
    c.output_q = 0;
    c.velocity_q = 0;
    return;
  }
  const SimMaestroChannel& limits = settings_[static_cast<std::size_t>(channel)];
  c.target_q = static_cast<std::uint16_t>(std::lround(std::clamp<double>(quarter_us, limits.min_us * 4, limits.max_us * 4)));
  // From "no pulses" the first pulse is the target itself: the device does not know where the
  // servo is, so no speed or acceleration limit applies.
  if (c.output_q == 0) c.output_q = c.target_q;
}

void MaestroServos::go_home() {
  for (int i = 0; i < channel_count(); ++i) {
    const SimMaestroChannel& ch = settings_[static_cast<std::size_t>(i)];
    if (!ch.home_ignore) set_target(i, maestro::quarter_us_from_us(ch.home_us));
  }
}

void MaestroServos::raise(std::uint16_t error_bits) {
  errors_ |= error_bits;
  go_home();  // on any error the Maestro sends its channels to their home positions
}

bool MaestroServos::moving() const {
  return std::any_of(channels_.begin(), channels_.end(),
                     [](const Channel& c) { return c.target_q != 0 && c.output_q != c.target_q; });
}

void MaestroServos::advance(double dt_s) {
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
void MaestroServos::move_output(Channel& c, double dt_s) {
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
