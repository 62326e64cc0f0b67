#pragma once
// The transport layer for USB devices driven by control transfers on endpoint 0 (vendor
// requests): moves one setup packet and its data stage with a deadline and knows nothing of
// servos. Implementations: LibusbControlTransport (a real device), and a simulated device's
// connection (sim::UsbDeviceHost).

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/usb_setup.hpp"

namespace avar::firmware_iface {

class UsbControlTransport {
 public:
  virtual ~UsbControlTransport() = default;

  /// One control transfer. Host to device (bit 7 of request_type clear): sends the first
  /// setup.length bytes of `data`; device to host: receives up to setup.length bytes into
  /// `data`. *transferred is set to the bytes moved (a device may answer fewer than asked).
  /// Returns ok; timeout when the deadline passed; bad_data when the device refused the request
  /// (a USB stall); io_error when the device is gone. Precondition: data.size() >= setup.length.
  /// Real-time safe in implementations: no allocation, no exception (the wait is the bus's).
  virtual Status control(const UsbSetup& setup, std::span<std::uint8_t> data, std::chrono::milliseconds timeout,
                         std::size_t* transferred) noexcept = 0;

  /// Finds and opens the device again after an io_error (unplugged and plugged back in).
  /// Returns ok once it is usable, io_error while it is still gone. Not real-time.
  virtual Status reopen() noexcept = 0;

  /// A name for messages: "USB (serial 00012345)".
  virtual const std::string& name() const noexcept = 0;
};

}  // namespace avar::firmware_iface
