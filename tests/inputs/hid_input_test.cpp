// The HID input source: spec parsing, the report thread against simulated reports (a real pad's
// descriptor), and the real hidapi path where this machine has HID devices (else it checks the
// "no HID devices" error and skips what needs a device, saying so).
#include "avar/inputs/hid_input.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <algorithm>
#include <deque>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "../support/hid_fixtures.hpp"

namespace avar::inputs {
namespace {

using namespace std::chrono_literals;
using Bytes = std::vector<std::uint8_t>;

std::string hid_in_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(HidInputSpec, ParsesVendorProductAndSerial) {
  HidDeviceSpec s = parse_hid_device_spec("054c:09cc");
  EXPECT_EQ(s.vendor_id, 0x054C);
  EXPECT_EQ(s.product_id, 0x09CC);
  EXPECT_EQ(s.serial, "");
  s = parse_hid_device_spec("46D:C216:ab:cd");  // the serial keeps its own colons
  EXPECT_EQ(s.vendor_id, 0x046D);
  EXPECT_EQ(s.product_id, 0xC216);
  EXPECT_EQ(s.serial, "ab:cd");
  EXPECT_EQ(hid_ids(0x054C, 0x09CC), "054c:09cc");
}

TEST(HidInputSpec, BadSpecsSayWhatIsExpected) {
  for (const char* bad : {"", "054c", "054c:", ":09cc", "054cc:09cc", "054c:09cg", "054c:09cc:", "usb:1:2"}) {
    const std::string what = hid_in_error([bad] { make_hid_input(bad); });
    EXPECT_NE(what.find("expected VID:PID or VID:PID:SERIAL with hex ids"), std::string::npos) << bad << ": " << what;
    EXPECT_THROW(parse_hid_device_spec(bad), std::invalid_argument) << bad;
  }
  EXPECT_NE(hid_in_error([] { make_hid_input("054c:xyz"); }).find("product id 'xyz'"), std::string::npos);
}

TEST(HidInputSpec, DescribesTheDeviceBeforeItIsOpened) {
  const std::unique_ptr<InputSource> in = make_hid_input("054c:09cc");
  EXPECT_EQ(in->describe(), "HID 054c:09cc");
  EXPECT_EQ(in->counters().messages, 0u);
  in->stop();  // before start: nothing to stop
}

TEST(HidInputSpec, SysfsDescriptorsOnlyForHidrawNodes) {
  EXPECT_NE(hid_in_error([] { read_hidraw_report_descriptor("/dev/usb/hiddev0"); }).find("not a hidraw node"), std::string::npos);
  EXPECT_NE(hid_in_error([] {
              read_hidraw_report_descriptor("/dev/hidraw9999");
            }).find("/sys/class/hidraw/hidraw9999/device/report_descriptor"),
            std::string::npos);
}

/// Reports handed out one per read(), then timeouts; -1 ("device gone") once told.
class HidInSimulatedReader final : public HidReportReader {
 public:
  void push(Bytes report) {
    const std::lock_guard lock(mutex_);
    queue_.push_back(std::move(report));
  }
  void unplug() {
    const std::lock_guard lock(mutex_);
    gone_ = true;
  }
  int read(std::span<std::uint8_t> buffer, std::chrono::milliseconds timeout) noexcept override {
    {
      const std::lock_guard lock(mutex_);
      if (!queue_.empty()) {
        const Bytes r = std::move(queue_.front());
        queue_.pop_front();
        const std::size_t n = std::min(r.size(), buffer.size());
        std::copy_n(r.begin(), n, buffer.begin());
        return static_cast<int>(n);
      }
      if (gone_) return -1;
    }
    std::this_thread::sleep_for(std::min(timeout, std::chrono::milliseconds(2)));
    return 0;
  }

 private:
  std::mutex mutex_;
  std::deque<Bytes> queue_;
  bool gone_ = false;
};

template <typename Condition>
bool hid_in_wait_for(Condition done) {
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(1ms);
  }
  return true;
}

TEST(HidReportPump, PostsDecodedReportsFromItsThreadUntilTheDeviceGoes) {
  const hid::ReportDescriptor layout = hid::parse_report_descriptor(testing::load_hid_fixture("logitech_f310_dinput.hex"));
  auto owned = std::make_unique<HidInSimulatedReader>();
  HidInSimulatedReader* reader = owned.get();
  HidReportPump pump(layout, std::move(owned), "HID 046d:c216 Logitech Dual Action");
  EXPECT_EQ(pump.control_names().front(), "x");
  testing::RecordingControlSink sink;
  pump.start(sink);
  reader->push(Bytes{0x80, 0x80, 0x80, 0x80, 0x08, 0x00, 0x00, 0x00});  // at rest
  reader->push(Bytes{0xFF, 0x80, 0x80, 0x80, 0x02, 0x01, 0x00, 0x00});  // x right, hat right, button 5
  ASSERT_TRUE(hid_in_wait_for([&] { return pump.counters().messages == 2; }));
  ASSERT_TRUE(hid_in_wait_for([&] { return sink.size() == pump.control_names().size() + 3; }));
  EXPECT_EQ(sink.value("x"), 1.0);
  EXPECT_EQ(sink.value("hat_x"), 1.0);
  EXPECT_EQ(sink.value("button5"), 1.0);
  const std::int64_t arrived = sink.posts().back().arrived_ns;
  EXPECT_GT(arrived, 0);
  EXPECT_EQ(pump.counters().ignored, 0u);
  EXPECT_EQ(pump.describe(), "HID 046d:c216 Logitech Dual Action");

  reader->unplug();
  ASSERT_TRUE(hid_in_wait_for([&] { return pump.disconnected(); }));
  EXPECT_EQ(pump.describe(), "HID 046d:c216 Logitech Dual Action (disconnected)");
  pump.stop();
  pump.stop();  // idempotent
}

TEST(HidReportPump, CountsReportsItCannotDecodeAndStopsPromptly) {
  const hid::ReportDescriptor layout = hid::parse_report_descriptor(testing::load_hid_fixture("dualshock4_v2_usb.hex"));
  auto owned = std::make_unique<HidInSimulatedReader>();
  owned->push(Bytes(78, 0x11));  // the Bluetooth report 0x11: not in the USB descriptor
  HidReportPump pump(layout, std::move(owned), "HID 054c:09cc Wireless Controller");
  testing::RecordingControlSink sink;
  pump.start(sink);
  ASSERT_TRUE(hid_in_wait_for([&] { return pump.counters().ignored == 1; }));
  EXPECT_EQ(pump.counters().messages, 1u);
  const auto t0 = std::chrono::steady_clock::now();
  pump.stop();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, 2s);
  EXPECT_EQ(sink.size(), 0u);
  EXPECT_FALSE(pump.disconnected());
}

TEST(HidInputDevice, MissingDevicesAreNamedInTheError) {
  std::vector<HidDeviceInfo> devices;
  try {
    devices = enumerate_hid_devices();
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "hidapi cannot start here: " << e.what();
  }
  testing::RecordingControlSink sink;
  const std::unique_ptr<InputSource> in = make_hid_input("ffff:fffe");
  const std::string what = hid_in_error([&] { in->start(sink); });
  if (devices.empty()) {
    EXPECT_NE(what.find("hidapi: no HID devices on this machine"), std::string::npos) << what;
    GTEST_SKIP() << "no HID devices on this machine (hidapi/hidraw enumerated none): the device-side checks need a "
                    "gamepad or other HID device plugged in";
  }
  EXPECT_NE(what.find("no HID device ffff:fffe (found: " + list_hid_devices(devices) + ")"), std::string::npos) << what;
}

TEST(HidInputDevice, OpensTheFirstGamepadFound) {
  std::vector<HidDeviceInfo> devices;
  try {
    devices = enumerate_hid_devices();
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "hidapi cannot start here: " << e.what();
  }
  const HidDeviceInfo* pad = nullptr;
  for (const HidDeviceInfo& d : devices)
    if (d.usage_page == 1 && (d.usage == 4 || d.usage == 5)) pad = &d;
  if (pad == nullptr)
    GTEST_SKIP() << "no HID gamepad or joystick on this machine (hidapi found: '" << list_hid_devices(devices) << "')";
  const std::unique_ptr<InputSource> in = make_hid_input(hid_ids(pad->vendor_id, pad->product_id));
  testing::RecordingControlSink sink;
  try {
    in->start(sink);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "the gamepad cannot be opened by this user: " << e.what();
  }
  EXPECT_NE(in->describe().find("HID " + hid_ids(pad->vendor_id, pad->product_id)), std::string::npos);
  std::this_thread::sleep_for(200ms);  // a pad at rest may send nothing: no assertion on posts
  in->stop();
}

}  // namespace
}  // namespace avar::inputs
