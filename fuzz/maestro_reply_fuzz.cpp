// What a Maestro answers on its serial port (Get Position, Get Errors replies, or noise): the
// link must read any reply into finite channel positions or report a status.
#include <cstddef>
#include <cstdint>

#include "avar/firmware_iface/maestro_link.hpp"
#include "scripted_transport.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fi = avar::firmware_iface;
  avar::fuzz::ByteReader in(data, size);
  avar::fuzz::ScriptedTransport transport(in);
  fi::MaestroLinkConfig config;
  const std::uint8_t options = in.u8();
  config.framing.pololu = (options & 1) != 0;
  config.framing.crc = (options & 2) != 0;
  config.channel_count = (options & 4) != 0 ? 6 : 24;
  for (std::size_t i = 0; i < 3; ++i) {
    fi::MaestroActuator a;
    a.channel = i;
    a.device_channel = static_cast<int>(i * 2);
    a.calibration.reverse = i == 1;
    config.actuators.push_back(a);
  }
  fi::MaestroLink link(transport, config);
  avar::fuzz::read_link_until_script_ends(link, in, [&] {
    std::uint16_t errors = 0;
    (void)link.read_errors(errors);
  });
  return 0;
}
