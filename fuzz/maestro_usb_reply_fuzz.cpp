// What a Maestro answers over native USB (Get Variables / Get Servo Settings replies of any
// length): the decoders must read a record only from a reply long enough to hold it.
#include <cstddef>
#include <cstdint>

#include "avar/firmware_iface/maestro_usb_codec.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace usb = avar::firmware_iface::maestro_usb;
  avar::fuzz::ByteReader in(data, size);
  static constexpr int kCounts[4] = {6, 12, 18, 24};
  const int channel_count = kCounts[in.u8() & 3];
  const auto reply = in.rest();
  std::uint16_t errors = 0;
  (void)usb::decode_errors(reply, &errors);
  for (int channel = 0; channel < channel_count; ++channel) {
    usb::ServoStatus status;
    (void)usb::decode_servo_status(reply, channel_count, channel, &status);
  }
  return 0;
}
