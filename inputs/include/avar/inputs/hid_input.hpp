#pragma once
// HID gamepads and joysticks as live input (input_source.hpp), through hidapi (hidraw backend).
// The device's own report descriptor is parsed (hid_report_descriptor.hpp), so any pad works,
// not one hard-coded layout; controls are named as hid_report_decoder.hpp says (x, y, rz,
// hat_x, button1, ...).
//
// Spec (the text after "hid:"): `VID:PID[:SERIAL]`, ids in hex ("054c:09cc",
// "046d:c216:ABC123"). Several devices with those ids and no serial: the first one that is a
// gamepad, joystick or multi-axis controller, else the first.
//
// The report descriptor: hidapi >= 0.14 gives it (hid_get_report_descriptor); older hidapi
// (0.13 on Debian 12) does not, so on Linux it is read from sysfs for the hidraw node that
// hidapi opened: /sys/class/hidraw/hidrawN/device/report_descriptor.
//
// Threads: start() opens the device and starts one thread that waits for reports
// (hid_read_timeout, 50 ms) and posts changed controls to the sink; stop() joins it. A device
// that goes away (unplugged) ends the thread; describe() then says "disconnected".

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "avar/inputs/hid_report_descriptor.hpp"
#include "avar/inputs/input_source.hpp"

namespace avar::inputs {

struct HidDeviceSpec {
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string serial;  ///< empty: any
};

/// "054c:09cc" or "054c:09cc:SERIAL": 1..4 hex digits each id. Throws std::invalid_argument
/// saying what was found and what is expected.
HidDeviceSpec parse_hid_device_spec(std::string_view spec);
/// "054c:09cc" (lower-case, 4 digits each).
std::string hid_ids(std::uint16_t vendor_id, std::uint16_t product_id);

/// A HID device hidapi can see.
struct HidDeviceInfo {
  std::string path;  ///< "/dev/hidraw3" with the hidraw backend
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string serial;
  std::string manufacturer;
  std::string product;
  std::uint16_t usage_page = 0;  ///< of the top-level collection (0 when hidapi does not say)
  std::uint16_t usage = 0;
  int interface_number = -1;
};

/// Every HID device hidapi can see (all ids). Throws std::runtime_error when hidapi cannot be
/// initialised. Not real-time.
std::vector<HidDeviceInfo> enumerate_hid_devices();
/// "046d:c216 Logitech Dual Action, 054c:09cc Wireless Controller", or "" for no devices.
std::string list_hid_devices(const std::vector<HidDeviceInfo>& devices);

/// Linux: the report descriptor of hidraw node `hidraw_path` ("/dev/hidraw3"), from
/// /sys/class/hidraw/hidraw3/device/report_descriptor. Throws std::runtime_error naming the file
/// when it cannot be read.
std::vector<std::uint8_t> read_hidraw_report_descriptor(const std::string& hidraw_path);

/// Where a HID input source's reports come from: the hidapi device, or a simulation.
class HidReportReader {
 public:
  virtual ~HidReportReader() = default;
  /// Waits up to `timeout` for one input report (numbered reports start with their id); returns
  /// its length, 0 on timeout, -1 when the device is gone. Called from the source's thread only.
  virtual int read(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) noexcept = 0;
};

/// The thread of a HID input source: reads reports from `reader`, decodes them with the
/// descriptor's layout and posts changed controls. Separate from hidapi so that it is tested with
/// simulated reports.
class HidReportPump {
 public:
  /// `description`: describe()'s text ("HID 054c:09cc Wireless Controller").
  HidReportPump(const hid::ReportDescriptor& descriptor, std::unique_ptr<HidReportReader> reader, std::string description);
  ~HidReportPump();
  HidReportPump(const HidReportPump&) = delete;
  HidReportPump& operator=(const HidReportPump&) = delete;

  /// Starts the thread delivering into `sink` (borrowed until stop()). Called once.
  void start(ControlSink& sink);
  /// Joins the thread; no post() after it returns. Idempotent.
  void stop() noexcept;
  /// The description, with " (disconnected)" once the reader reported the device gone.
  std::string describe() const;
  /// messages: reports read; ignored: reports of unknown id or empty. Any thread.
  InputCounters counters() const noexcept;
  /// The reader reported the device gone (the thread has ended). Any thread.
  bool disconnected() const noexcept;
  /// Names of the controls the device's reports carry (fixed at construction).
  std::vector<std::string> control_names() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The InputSource for `spec` (the text after "hid:", see above). Throws std::invalid_argument
/// for a malformed spec; opens nothing until start(), which throws std::runtime_error: "no HID
/// device 054c:09cc (found: 046d:c216 Logitech Dual Action)", "hidapi: no HID devices on this
/// machine", a device that cannot be opened (permissions: a udev rule), an unreadable or
/// malformed report descriptor.
std::unique_ptr<InputSource> make_hid_input(std::string_view spec);

}  // namespace avar::inputs
