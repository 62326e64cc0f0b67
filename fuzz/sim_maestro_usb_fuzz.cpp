// Control transfers a host sends a simulated Maestro over native USB (vendor requests, any
// setup packet): the device must answer within wLength or stall, never write past the data stage.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "avar/sim/sim_maestro_usb.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  avar::fuzz::ByteReader in(data, size);
  avar::sim::SimMaestroConfig config;
  static constexpr int kCounts[4] = {6, 12, 18, 24};
  config.channel_count = kCounts[in.u8() & 3];
  avar::sim::SimMaestroUsb device(config);
  while (!in.empty()) {
    avar::firmware_iface::UsbSetup setup;
    setup.request_type = in.u8();
    setup.request = in.u8();
    setup.value = in.u16();
    setup.index = in.u16();
    setup.length = static_cast<std::uint16_t>(in.u16() % 1025);
    // Exactly the data stage, on the heap: ASan catches a device that writes past it.
    std::vector<std::uint8_t> stage(setup.length);
    if (!setup.device_to_host()) {
      const auto payload = in.take(setup.length);
      std::copy(payload.begin(), payload.end(), stage.begin());
    }
    std::size_t transferred = 0;
    if (device.control(setup, stage, &transferred) == avar::Status::ok && transferred > setup.length) std::abort();
    device.advance(in.u8() / 1000.0);
  }
  return 0;
}
