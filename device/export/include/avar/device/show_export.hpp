#pragma once
// The host's side of the device engine: a show's curves encoded as a device show image
// (avar/device/show_image.hpp), checked against what the engine can play. Load-time code:
// allocates and throws InputError naming the key that cannot be encoded.

#include <cstdint>
#include <string>
#include <vector>

#include "avar/device/limiter.hpp"
#include "avar/playback/runtime/curve.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::device {

/// The channel units mapped to output 0 and 65535 (a rig channel's min and max).
struct OutputRange {
  double low = 0;
  double high = 1;
  /// Output units (unrounded) of a value in channel units, and back.
  double to_output(double value) const noexcept { return (value - low) / (high - low) * 65535.0; }
  double to_channel(double output) const noexcept { return low + output / 65535.0 * (high - low); }
};

/// One channel of an image: the show track that drives it and its range.
struct ImageChannel {
  std::string name;
  OutputRange range;
};

struct ImageOptions {
  /// Ticks per second of the image; 0 chooses the smallest of kTickRates on which every key time,
  /// and every time in `on_grid`, falls on a whole tick.
  std::uint32_t ticks_per_second = 0;
  std::vector<double> on_grid;  ///< seconds that must be whole ticks (a sampling step, its start)
};

/// The tick rates an image may choose from, smallest first: those of frame rates (24, 25, 30,
/// 48, 50, 60, 120 fps) with milliseconds, and microseconds, where any time rounds to a tick.
inline constexpr std::uint32_t kTickRates[] = {1000, 24000, 30000, 48000, 50000, 60000, 120000, 600000, 1000000};

/// The smallest of kTickRates on which every time given falls on a whole tick, else the last.
std::uint32_t choose_ticks_per_second(const std::vector<double>& times_s);

/// An encoded show.
struct ShowImage {
  std::vector<std::uint8_t> bytes;
  std::uint32_t ticks_per_second = 0;
  std::size_t keys = 0;         ///< over every channel
  std::size_t bezier_keys = 0;  ///< keys that start a Bezier segment solved in time
  std::size_t key_bytes = 0;    ///< bytes of the keys alone (without headers and channel records)
};

/// Encodes the tracks of `show` that drive `channels`, in that order. Throws InputError for a
/// show with layers, clips or targets (their composition is the host's), a channel without a
/// track, a key time that does not fit 32-bit ticks, keys closer than a tick, a Bezier segment
/// whose time runs backwards, a key or handle beyond 16 ranges of its channel, a B-spline that
/// meets another family with a jump.
ShowImage encode_show_image(const playback::Show& show, const std::vector<ImageChannel>& channels,
                            const ImageOptions& options = {});

/// A channel's limits for the device's limiter at `rate` control ticks per second, from the rig's
/// numbers in channel units: the range less the soft margin, the rest pose, the speed (units per
/// second) and acceleration (units per second squared). Throws std::invalid_argument for limits
/// the limiter cannot use (no room inside the margin, a rest outside it, speed or acceleration
/// not above 0).
ChannelLimits device_limits(OutputRange range, double rest, double max_velocity, double max_acceleration, double soft_margin,
                            std::uint32_t rate);

/// The acceleration headroom of a streaming board's limits (streaming_limits).
inline constexpr double kStreamAccelHeadroom = 1.25;
/// A streaming board's limits (avar-device): device_limits with the acceleration kStreamAccelHeadroom
/// times the rig's. avar's own limiter has shaped the motion at its tick rate; the cubic between
/// knots, sampled at the board's own rate, asks up to about a fifth more acceleration between
/// avar's ticks, which the board's limiter must not trim (it would lag the figure behind the
/// show), while it still catches what a faulty stream asks. Range, rest and speed are the rig's.
ChannelLimits streaming_limits(OutputRange range, double rest, double max_velocity, double max_acceleration, double soft_margin,
                               std::uint32_t rate);

/// One curve's channel record (the image's channel layout), for tests and tools.
std::vector<std::uint8_t> encode_channel_record(const playback::RawCurve& raw, const playback::Curve& curve, OutputRange range,
                                                std::uint32_t ticks_per_second, ShowImage* counts = nullptr);

/// A minimal image of one channel: a test's or a tool's way to play one curve on the engine.
std::vector<std::uint8_t> single_channel_image(const std::vector<std::uint8_t>& record, std::uint32_t ticks_per_second,
                                               std::int32_t duration_ticks);

}  // namespace avar::device
