// What an SSC-32 answers (Q movement and QP pulse-width replies, or noise): the link must read
// any reply into finite channel positions or report a status.
#include <cstddef>
#include <cstdint>

#include "avar/firmware_iface/ssc32_link.hpp"
#include "scripted_transport.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fi = avar::firmware_iface;
  avar::fuzz::ByteReader in(data, size);
  avar::fuzz::ScriptedTransport transport(in);
  fi::Ssc32LinkConfig config;
  for (std::size_t i = 0; i < 3; ++i) {
    fi::Ssc32Actuator a;
    a.channel = i;
    a.device_channel = static_cast<int>(31 - i * 7);
    a.calibration.reverse = i == 2;
    config.actuators.push_back(a);
  }
  fi::Ssc32Link link(transport, config);
  avar::fuzz::read_link_until_script_ends(link, in, [&] {
    bool moving = false;
    (void)link.query_moving(moving);
  });
  return 0;
}
