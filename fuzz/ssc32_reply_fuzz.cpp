// What an SSC-32 answers (Q movement and QP pulse-width replies, or noise): the link must read
// any reply into finite channel positions or report a status.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

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
  std::vector<double> frame(3, 0.0);
  while (!in.empty()) {
    if (in.flag()) {
      bool moving = false;
      (void)link.query_moving(moving);
      continue;
    }
    bool flags[3] = {false, false, false};
    if (link.read_positions(frame, flags) != avar::Status::ok) continue;
    for (std::size_t i = 0; i < 3; ++i)
      if (flags[i] && !std::isfinite(frame[i])) std::abort();
  }
  return 0;
}
