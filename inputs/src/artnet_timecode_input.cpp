#include "avar/inputs/artnet_timecode_codec.hpp"
#include "avar/inputs/timecode_inputs.hpp"

namespace avar::inputs {

ArtnetTimecodeInput::ArtnetTimecodeInput(std::string host, std::uint16_t port)
    : listener_(std::move(host), port, "Art-Net timecode") {}

void ArtnetTimecodeInput::start() {
  listener_.start([this](std::span<const std::uint8_t> datagram, std::int64_t arrived_ns) {
    Timecode t;
    switch (artnet::decode_timecode(datagram, t)) {
      case artnet::TimeCodeVerdict::ok:
        mailbox_.publish(TimecodeFix{t, 0.0, false}, arrived_ns);
        counters_.add(&TimecodeCounters::fixes);
        return;
      case artnet::TimeCodeVerdict::other_opcode: counters_.add(&TimecodeCounters::ignored); return;
      default: counters_.add(&TimecodeCounters::bad); return;
    }
  });
}

}  // namespace avar::inputs
