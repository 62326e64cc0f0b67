#pragma once
// A simulated Pololu Micro/Mini Maestro on its native USB interface
// (firmware_iface/maestro_usb_codec.hpp): it answers the vendor control requests a driver uses
// (Set Target, Set Servo Variable for speed and acceleration, Clear Errors, Get Variables in the
// Micro or Mini layout, Get Servo Settings on a Mini) with the exact reply layouts, and stalls
// every other request, a wrong request type, a data stage where none belongs, and Get Servo
// Settings on a Micro Maestro. Its channels are the same model as the serial simulator's
// (MaestroServos: targets clamped to the channel's range, speed and acceleration limits, one
// ServoModel per channel).
//
// Behaviour the SDK leaves open, as modelled here: a request for a channel the device does not
// have is stalled; an in-request may ask for fewer bytes than the reply has (the device sends the
// first wLength bytes). The serial settings of the configuration (device number, CRC, baud
// detection, Mini SSC offset) play no part on USB.
//
// Not thread-safe: a host (UsbDeviceHost) serialises every call.

#include <cstdint>
#include <deque>
#include <string>

#include "avar/sim/maestro_servos.hpp"
#include "avar/sim/usb_control_device.hpp"

namespace avar::sim {

class SimMaestroUsb final : public UsbControlDevice {
 public:
  /// Throws std::invalid_argument as MaestroServos does. `serial` is the serial number string
  /// the device reports (for its host's name).
  explicit SimMaestroUsb(SimMaestroConfig config, std::string serial = "00000000");

  Status control(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* transferred) override;
  void advance(double dt_s) override { servos_.advance(dt_s); }

  /// The USB product id of this model (0x0089 Micro 6 ... 0x008C Mini 24).
  std::uint16_t product_id() const;
  const std::string& serial() const { return serial_; }

  // Inspection and fault injection. Precondition: 0 <= channel < channel_count.
  std::uint16_t target(int channel) const { return servos_.target(channel); }
  double output_pulse(int channel) const { return servos_.output_pulse(channel); }
  double servo_position_us(int channel) const { return servos_.servo_position_us(channel); }
  std::uint16_t speed(int channel) const { return servos_.speed(channel); }
  std::uint16_t acceleration(int channel) const { return servos_.acceleration(channel); }
  std::uint16_t errors() const { return servos_.errors(); }
  /// Latches error bits (and sends the channels home), as a serial or script error would.
  void raise(std::uint16_t error_bits) { servos_.raise(error_bits); }
  /// The last log_limit setup packets received, oldest first (stalled ones too).
  const std::deque<firmware_iface::UsbSetup>& log() const { return log_; }
  /// Requests stalled since construction.
  std::uint64_t stalls() const { return stalls_; }

 private:
  Status out_request(const firmware_iface::UsbSetup& setup);
  Status in_request(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* transferred);
  /// Writes the servo records of every channel into reply from offset `at` on.
  void write_records(std::span<std::uint8_t> reply, std::size_t at) const;

  SimMaestroConfig config_;
  MaestroServos servos_;
  std::string serial_;
  std::deque<firmware_iface::UsbSetup> log_;
  std::uint64_t stalls_ = 0;
};

}  // namespace avar::sim
