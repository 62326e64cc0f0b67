// Bytes from an ENTTEC DMX USB Pro (widget parameter and serial number replies, noise), framed
// message by message as the link does: every verdict must make progress and stay in the input.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/firmware_iface/dmx_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace dmx = avar::firmware_iface::dmx;
  std::span<const std::uint8_t> in(data, size);
  while (!in.empty()) {
    dmx::Message message;
    std::size_t consumed = 0;
    const dmx::DecodeResult r = dmx::decode_message(in, &message, &consumed);
    if (r == dmx::DecodeResult::need_more) break;
    if (consumed == 0 || consumed > in.size()) std::abort();
    if (r == dmx::DecodeResult::ok) {
      if (message.data.data() < in.data() || message.data.data() + message.data.size() > in.data() + in.size()) std::abort();
      dmx::WidgetParameters p;
      (void)dmx::decode_widget_parameters(message.data, &p);
    }
    in = in.subspan(consumed);
  }
  return 0;
}
