// Lines from an SLCAN adapter (frames with and without timestamps, error and state lines, acks,
// status, version): the decoder splits the bytes at CR as the transport does and must classify
// any line, keeping every frame within its 0..8 bytes.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/firmware_iface/slcan_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace slcan = avar::firmware_iface::slcan;
  std::span<const std::uint8_t> in(data, size);
  while (!in.empty()) {
    const auto cr = std::find(in.begin(), in.end(), std::uint8_t{'\r'});
    const auto length = static_cast<std::size_t>(cr - in.begin());
    const slcan::Line line = slcan::parse_line(in.first(length));
    if (line.frame.dlc > 8) std::abort();
    if (line.kind == slcan::LineKind::frame && line.frame.id > (line.frame.extended ? 0x1FFF'FFFFu : 0x7FFu)) std::abort();
    in = in.subspan(std::min(length + 1, in.size()));
  }
  return 0;
}
