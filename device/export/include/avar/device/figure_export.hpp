#pragma once
// The host's side of a device figure (avar/device/figure.hpp): the rig's channels that a device
// drives, their limits for the device's limiter and their servo pulses, and the figure record
// that carries them to flash. Load-time code: allocates and throws InputError naming the rig
// file's line of what a device cannot drive.

#include <cstdint>
#include <string>
#include <vector>

#include "avar/device/limiter.hpp"
#include "avar/device/show_export.hpp"
#include "avar/rig/rig.hpp"

namespace avar::device {

/// A PCA9685 board of the figure (a rig link of protocol pca9685).
struct FigureBoardSpec {
  std::string link;  ///< the rig link's name
  int address = 0x40;
  int frequency_hz = 50;
  std::uint32_t clock_hz = 25000000;
  std::uint8_t prescale = 0;
  bool totem_pole = true;
};

/// One channel a device drives.
struct FigureChannelSpec {
  std::string name;  ///< the rig channel
  OutputRange range;
  ChannelLimits limits;  ///< at the figure's rate
  std::size_t board = 0;
  bool on_pin = false;                         ///< on the device's own pin (a pwm link), not a board
  int output = 0;                              ///< 0..15 on a board; the pin
  std::int32_t at_low_ns = 0, at_high_ns = 0;  ///< the pulse at output 0 (the channel's min) and 65535
  double rest = 0;                             ///< channel units
};

struct FigureSpec {
  std::string rig;
  std::uint32_t rate = 50;     ///< control ticks per second (the rig's rate_hz)
  std::uint32_t pin_rate = 0;  ///< the pins' pulses per second (the pwm link's frequency; 0: no pins)
  std::vector<FigureBoardSpec> boards;
  std::vector<FigureChannelSpec> channels;  ///< the rig's channels with an actuator, in rig order
};

/// The figure a device drives from `rig`: every channel with an actuator, which must sit on a
/// PCA9685 link or on the rig's one pwm link (the device's own pins, pulses within 544 to 2400 µs);
/// the rate must be a whole number of ticks per second.
/// Throws InputError at the link, actuator or channel a device cannot drive.
FigureSpec figure_from_rig(const rig::Rig& rig);

/// The figure of a board that runs avar's streaming player (avar export --stream): every channel
/// with an actuator, which must sit on the rig's avar-device link; output n drives output n % 16
/// of the PCA9685 at 0x40 + n / 16 (50 Hz, the internal 25 MHz oscillator), over the actuator's
/// pulse range; the limits are streaming_limits at the link's device_rate, which is the record's
/// rate. Throws InputError where figure_from_rig does, and for a rig without an avar-device link.
FigureSpec stream_figure_from_rig(const rig::Rig& rig);

/// The figure record (figure.hpp's layout).
std::vector<std::uint8_t> encode_figure_record(const FigureSpec& figure);

/// The figure's channels as the show encoder takes them.
std::vector<ImageChannel> image_channels(const FigureSpec& figure);

}  // namespace avar::device
