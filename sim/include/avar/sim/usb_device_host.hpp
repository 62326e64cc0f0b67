#pragma once
// Serves a simulated USB device (UsbControlDevice) to drivers in this process: connect() gives a
// firmware_iface::UsbControlTransport, as opening the real device through libusb does, so the
// real driver runs unchanged against the simulator. Transfers are answered at once, under the
// host's mutex; the owner reaches the device under the same mutex (with_device) to advance its
// time or inspect it. The device can be unplugged and plugged back (fault injection).
//
// Thread safety: every member may be called from any thread (a link's I/O thread transfers
// while the loop thread advances time). The device and the host must outlive the connections.

#include <memory>
#include <mutex>
#include <string>

#include "avar/firmware_iface/usb_control_transport.hpp"
#include "avar/sim/usb_control_device.hpp"

namespace avar::sim {

class UsbDeviceHost {
 public:
  /// `name` names the connection in messages ("USB (serial 00012345)").
  UsbDeviceHost(UsbControlDevice& device, std::string name);
  UsbDeviceHost(const UsbDeviceHost&) = delete;
  UsbDeviceHost& operator=(const UsbDeviceHost&) = delete;

  /// A new connection to the device.
  std::unique_ptr<firmware_iface::UsbControlTransport> connect();

  /// Runs f(UsbControlDevice&) with transfers kept away; returns what f returns.
  template <class F>
  auto with_device(F&& f) {
    std::lock_guard lock(mutex_);
    return f(device_);
  }

  /// Unplugged: every transfer fails with io_error and reopening fails, until plugged again.
  void set_plugged(bool plugged);
  /// Transfers answered since construction (any outcome but unplugged).
  std::uint64_t transfers() const;

 private:
  class Connection;

  mutable std::mutex mutex_;
  UsbControlDevice& device_;
  std::string name_;
  bool plugged_ = true;
  std::uint64_t transfers_ = 0;
};

}  // namespace avar::sim
