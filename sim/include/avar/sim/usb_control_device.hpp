#pragma once
// The seam between a simulated USB device driven by control transfers (vendor requests on
// endpoint 0) and whatever carries them (UsbDeviceHost). A device answers exactly what the real
// one answers and stalls what the real one refuses. Not thread-safe: its host serialises calls.

#include <cstddef>
#include <cstdint>
#include <span>

#include "avar/core/status.hpp"
#include "avar/firmware_iface/usb_setup.hpp"

namespace avar::sim {

class UsbControlDevice {
 public:
  virtual ~UsbControlDevice() = default;
  /// One control transfer as the device sees it. Host to device: the data stage is
  /// data.first(setup.length). Device to host: writes its answer, at most setup.length bytes,
  /// into data. Sets *transferred; returns ok, or bad_data for a request the device stalls.
  /// Precondition: data.size() >= setup.length.
  virtual Status control(const firmware_iface::UsbSetup& setup, std::span<std::uint8_t> data, std::size_t* transferred) = 0;
  /// Advances the device's simulated time by dt_s seconds.
  virtual void advance(double dt_s) = 0;
};

}  // namespace avar::sim
