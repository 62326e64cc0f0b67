#pragma once
// The minimum-jerk move 10x³ − 15x⁴ + 6x⁵ (rest to rest, smooth in velocity and acceleration) and
// the shortest duration of such a move within a share of a channel's limits. Real-time safe.

#include "avar/playback/runtime/idle_spec.hpp"

namespace avar::playback {

/// Progress 0..1 of a minimum-jerk move at fraction x of its duration (clamped to [0, 1]).
double min_jerk(double x) noexcept;

/// Peak |velocity|, |acceleration| and |jerk| of a minimum-jerk move of amplitude A over T:
/// these factors times A/T, A/T², A/T³.
inline constexpr double kMinJerkPeakVelocity = 1.875;
inline constexpr double kMinJerkPeakAcceleration = 5.773502691896258;  // 10/√3
inline constexpr double kMinJerkPeakJerk = 60.0;

/// The shortest duration (s) of a minimum-jerk move of `amplitude` (channel units) whose peak
/// velocity, acceleration and jerk stay within `share` (0..1] of the channel's limits, and at
/// least `at_least`.
double min_jerk_duration(double amplitude, const IdleChannelLimits& limits, double share, double at_least) noexcept;

}  // namespace avar::playback
