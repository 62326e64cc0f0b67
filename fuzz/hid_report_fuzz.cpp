// A HID device's report descriptor and input reports (gamepads, joysticks, anything that claims
// to be one): the descriptor parser must accept it or throw HidDescriptorError; every report
// then decodes into controls within their ranges. Input: a length byte pair for the descriptor,
// the descriptor, then reports of up to 64 bytes, each after a length byte.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "avar/inputs/hid_report_decoder.hpp"
#include "avar/inputs/hid_report_descriptor.hpp"
#include "fuzz_bytes.hpp"

namespace {

class HidFuzzRangeSink final : public avar::inputs::ControlSink {
 public:
  void post(std::string_view control, double value, bool bipolar, std::int64_t) noexcept override {
    if (control.empty() || !(value >= (bipolar ? -1.0 : 0.0) && value <= 1.0)) std::abort();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace hid = avar::inputs::hid;
  avar::fuzz::ByteReader in(data, size);
  const auto descriptor_bytes = in.take(in.u16() % 1024);
  try {
    const hid::ReportDescriptor descriptor = hid::parse_report_descriptor(descriptor_bytes);
    hid::ReportDecoder decoder(descriptor);
    HidFuzzRangeSink sink;
    std::int64_t now = 0;
    while (!in.empty()) (void)decoder.decode(in.take(in.u8() % 65), sink, ++now);
  } catch (const hid::HidDescriptorError&) {
  }
  return 0;
}
