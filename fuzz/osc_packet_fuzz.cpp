// A UDP datagram to avar's OSC input (a message, or bundles nested up to 8 deep), decoded by
// liblo and dispatched to controls: any datagram must be taken or counted as ignored.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "avar/firmware_iface/osc_input.hpp"

namespace {

class OscFuzzSink final : public avar::firmware_iface::ControlSink {
 public:
  void post(std::string_view control, double value, bool, std::int64_t) noexcept override {
    if (control.empty() || !std::isfinite(value)) std::abort();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  OscFuzzSink sink;
  const avar::firmware_iface::InputCounters counters = avar::firmware_iface::dispatch_osc_packet({data, size}, sink, 0);
  if (counters.ignored > counters.messages) std::abort();
  return 0;
}
