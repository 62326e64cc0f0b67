// The thin libusb path: on a machine without USB, or without a Maestro on it, opening fails with a
// message naming what is missing (and the hardware tests skip with it); with a Maestro attached
// they read its variables and drive it through the real driver.
#include "avar/firmware_iface/libusb_control_transport.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/firmware_iface/maestro_usb_codec.hpp"
#include "avar/firmware_iface/maestro_usb_link.hpp"

namespace avar::firmware_iface {
namespace {

using namespace std::chrono_literals;

UsbDeviceQuery any_maestro_query() {
  return {maestro_usb::kVendorId, {maestro_usb::kProductIds.begin(), maestro_usb::kProductIds.end()}, "", "Maestro"};
}

/// The only Maestro attached, or null with *missing saying what is missing.
std::unique_ptr<LibusbControlTransport> libusb_maestro_or_missing(std::string* missing) {
  try {
    return std::make_unique<LibusbControlTransport>(any_maestro_query());
  } catch (const std::runtime_error& e) {
    *missing = e.what();
    return nullptr;
  }
}

TEST(LibusbControlTransport, SaysWhatIsMissingWhenNoMaestroCanBeOpened) {
  std::string missing;
  if (libusb_maestro_or_missing(&missing)) GTEST_SKIP() << "a Maestro is attached: nothing is missing here";
  const bool no_usb = missing.rfind("libusb: no USB on this machine (", 0) == 0;
  const bool no_maestro = missing.rfind("no Maestro on USB (found: ", 0) == 0 || missing.rfind("several Maestros on USB", 0) == 0;
  EXPECT_TRUE(no_usb || no_maestro) << missing;
}

TEST(LibusbControlTransport, ASerialNumberThatIsNotThereIsNamedWithWhatWasFound) {
  UsbDeviceQuery query = any_maestro_query();
  query.serial = "00123456";
  try {
    LibusbControlTransport transport(query);
    GTEST_SKIP() << "a Maestro with serial 00123456 is attached";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    if (message.rfind("libusb: no USB on this machine", 0) == 0) GTEST_SKIP() << message;
    EXPECT_EQ(message.rfind("no Maestro with serial 00123456 on USB (found: ", 0), 0u) << message;
  }
}

TEST(LibusbControlTransport, DescribesWhatItFound) {
  EXPECT_EQ(describe_found({}), "none");
  EXPECT_EQ(describe_found({{0x008A, "00012345", ""}, {0x0089, "", "cannot open it: LIBUSB_ERROR_ACCESS"}}),
            "00012345 (0x008A), a device whose serial could not be read (0x0089): cannot open it: LIBUSB_ERROR_ACCESS");
}

TEST(LibusbControlTransport, ReadsARealMaestrosVariables) {
  std::string missing;
  auto transport = libusb_maestro_or_missing(&missing);
  if (!transport) GTEST_SKIP() << missing;
  const int channels = maestro_usb::channels_for_product_id(transport->product_id());
  ASSERT_NE(channels, 0);
  std::vector<std::uint8_t> reply(maestro_usb::kMaxReplySize);
  std::size_t got = 0;
  const UsbSetup setup = maestro_usb::get_positions(channels);
  ASSERT_EQ(transport->control(setup, reply, 500ms, &got), Status::ok);
  EXPECT_EQ(got, setup.length);
  // A request the Maestro does not know is stalled.
  ASSERT_EQ(transport->control({0xC0, 0x7F, 0, 0, 1}, reply, 500ms, &got), Status::bad_data);
}

TEST(LibusbControlTransport, DrivesARealMaestroThroughTheDriver) {
  std::string missing;
  auto transport = libusb_maestro_or_missing(&missing);
  if (!transport) GTEST_SKIP() << missing;
  const int channels = maestro_usb::channels_for_product_id(transport->product_id());
  // Channel 0 only, between 1400 and 1600 µs: safe for any servo plugged in.
  MaestroUsbLinkConfig config;
  config.channel_count = channels;
  LinearCalibration calibration;
  calibration.channel_min = 0;
  calibration.channel_max = 1;
  calibration.device_at_min = 1400;
  calibration.device_at_max = 1600;
  config.actuators.push_back({0, 0, calibration, 2000.0, std::nullopt});
  MaestroUsbLink link(std::move(transport), config);
  ASSERT_EQ(link.start(), Status::ok) << link.start_problem();
  const std::vector<double> frame{0.5};
  ASSERT_EQ(link.send(frame), Status::ok);
  std::vector<ChannelTelemetry> telemetry(1);
  link.read_telemetry(telemetry);
  EXPECT_EQ(telemetry[0].updates, 1u);
  EXPECT_EQ(link.release(), Status::ok);
}

}  // namespace
}  // namespace avar::firmware_iface
