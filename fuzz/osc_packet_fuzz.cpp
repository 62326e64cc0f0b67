// A UDP datagram to avar's OSC input (a message, or bundles nested up to 8 deep), decoded by
// liblo and dispatched to controls: any datagram must be taken or counted as ignored.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "avar/inputs/osc_input.hpp"

namespace {

class OscFuzzSink final : public avar::inputs::ControlSink {
 public:
  void post(std::string_view control, double value, bool, std::int64_t) noexcept override {
    if (control.empty() || !std::isfinite(value)) std::abort();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  OscFuzzSink sink;
  const avar::inputs::InputCounters counters = avar::inputs::dispatch_osc_packet({data, size}, sink, 0);
  if (counters.ignored > counters.messages) std::abort();
  return 0;
}
