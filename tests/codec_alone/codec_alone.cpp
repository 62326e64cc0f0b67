// Links avar::firmware_codec and nothing else of avar (no GoogleTest either): the pure codecs stand
// alone, as they must to compile for a microcontroller later. Encodes a CAN frame as an SLCAN line
// and a Maestro target command, compares both with the bytes of the protocol notes, and decodes the
// SLCAN line back. Prints one line per check; exits 1 on a wrong byte.
#include <array>
#include <cstdint>
#include <cstdio>
#include <span>

#include "avar/firmware_iface/can_frame.hpp"
#include "avar/firmware_iface/maestro_codec.hpp"
#include "avar/firmware_iface/slcan_codec.hpp"

namespace {

namespace fi = avar::firmware_iface;

bool same(std::span<const std::uint8_t> got, std::span<const std::uint8_t> want) {
  if (got.size() != want.size()) return false;
  for (std::size_t i = 0; i < got.size(); ++i)
    if (got[i] != want[i]) return false;
  return true;
}

bool check(const char* what, bool ok) {
  std::printf("%s: %s\n", what, ok ? "ok" : "WRONG");
  return ok;
}

}  // namespace

int main() {
  bool ok = true;

  const std::array<std::uint8_t, 2> payload{0x11, 0x22};
  const fi::CanFrame frame = fi::can_data_frame(0x123, payload);
  std::array<std::uint8_t, fi::slcan::kMaxLineLength> line{};
  const std::size_t length = fi::slcan::encode_frame(line, frame);
  const std::array<std::uint8_t, 10> want{'t', '1', '2', '3', '2', '1', '1', '2', '2', fi::slcan::kCr};
  ok &= check("slcan encode", same(std::span(line).first(length), want));

  const fi::slcan::Line decoded = fi::slcan::parse_line(std::span<const std::uint8_t>(line).first(length - 1));
  ok &= check("slcan decode", decoded.kind == fi::slcan::LineKind::frame && decoded.frame == frame);

  // Set Target, channel 0, 6000 quarter-microseconds (1.5 ms), compact framing.
  std::array<std::uint8_t, fi::maestro::kMaxPacketSize> packet{};
  const std::size_t size = fi::maestro::encode_set_target(packet, fi::maestro::Framing{}, 0, 6000);
  const std::array<std::uint8_t, 4> target{0x84, 0x00, 0x70, 0x2E};
  ok &= check("maestro set target", same(std::span(packet).first(size), target));

  return ok ? 0 : 1;
}
