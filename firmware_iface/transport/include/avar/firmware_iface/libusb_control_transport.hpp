#pragma once
// Control transfers to a real USB device through libusb-1.0: the device is found by vendor id,
// a list of product ids and (optionally) its serial number string. Only endpoint 0 is used, so
// no interface is claimed and the kernel drivers of the device's other interfaces (the Maestro's
// virtual serial ports) stay bound.
//
// Threads: one thread at a time calls control() and reopen() (the link's). Real time: each
// transfer waits on the bus, and libusb allocates inside a synchronous transfer; a real-time
// loop drives it from the link's own I/O thread (control::ThreadedLink), never from the tick.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "avar/firmware_iface/usb_control_transport.hpp"

namespace avar::firmware_iface {

/// Which device to open.
struct UsbDeviceQuery {
  std::uint16_t vendor_id = 0;
  std::vector<std::uint16_t> product_ids;
  std::string serial;       ///< the serial number string; empty: the only matching device present
  std::string device_name;  ///< for messages: "Maestro"
};

/// A matching device seen on the bus while searching.
struct UsbDeviceFound {
  std::uint16_t product_id = 0;
  std::string serial;   ///< empty when it could not be read (the device could not be opened)
  std::string problem;  ///< why the serial could not be read, else empty
};

/// "00012345 (0x008A), 00054321 (0x0089)" or "none", for messages.
std::string describe_found(const std::vector<UsbDeviceFound>& found);

class LibusbControlTransport final : public UsbControlTransport {
 public:
  /// Finds and opens the device. Throws std::runtime_error naming what is missing:
  /// "libusb: no USB on this machine (...)" when libusb cannot start or sees no bus;
  /// "no Maestro with serial 00123456 on USB (found: ...)"; "no Maestro on USB (found: none)";
  /// "several Maestros on USB (found: ...); name one by its serial number";
  /// "cannot open the Maestro with serial ...: ..." (permissions: a udev rule is missing).
  explicit LibusbControlTransport(UsbDeviceQuery query);
  ~LibusbControlTransport() override;
  LibusbControlTransport(const LibusbControlTransport&) = delete;
  LibusbControlTransport& operator=(const LibusbControlTransport&) = delete;

  Status control(const UsbSetup& setup, std::span<std::uint8_t> data, std::chrono::milliseconds timeout,
                 std::size_t* transferred) noexcept override;
  /// Searches for the same device (by the serial number it had) and opens it again.
  Status reopen() noexcept override;
  const std::string& name() const noexcept override { return name_; }

  /// The product id of the device opened.
  std::uint16_t product_id() const noexcept { return product_id_; }
  /// Its serial number string.
  const std::string& serial() const noexcept { return query_.serial; }

 private:
  struct Handles;
  /// Opens the device of query_; throws as the constructor.
  void open();
  void close() noexcept;

  UsbDeviceQuery query_;
  std::unique_ptr<Handles> handles_;
  std::uint16_t product_id_ = 0;
  std::string name_;
};

}  // namespace avar::firmware_iface
