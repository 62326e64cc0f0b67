#include "avar/assembly/protocol.hpp"

#include <stdexcept>

#include "avar/assembly/can_protocol.hpp"
#include "avar/assembly/dmx_protocol.hpp"
#include "avar/assembly/dynamixel_protocol.hpp"
#include "avar/assembly/feetech_protocol.hpp"
#include "avar/assembly/gpio_protocol.hpp"
#include "avar/assembly/maestro_protocol.hpp"
#include "avar/assembly/network_dmx_protocol.hpp"
#include "avar/assembly/ssc32_protocol.hpp"
#include "avar/firmware_iface/serial_transport.hpp"

namespace avar::assembly {

const std::vector<const Protocol*>& protocols() {
  static const std::vector<const Protocol*> all{&maestro_protocol(), &dynamixel_protocol(), &feetech_protocol(),
                                                &ssc32_protocol(),   &dmx_protocol(),       &can_protocol(),
                                                &gpio_protocol(),    &artnet_protocol(),    &sacn_protocol()};
  return all;
}

const Protocol* find_protocol(std::string_view name) {
  for (const Protocol* p : protocols())
    if (name == p->name) return p;
  return nullptr;
}

const Protocol& protocol_of(const rig::LinkSpec& link) {
  if (const Protocol* p = find_protocol(link.protocol)) return *p;
  throw std::invalid_argument("link '" + link.name + "' speaks an unknown protocol '" + link.protocol + "'");
}

std::string protocol_names() {
  std::string names;
  for (const Protocol* p : protocols()) names += (names.empty() ? "" : ", ") + std::string(p->name);
  return names;
}

int checked_baud(const Protocol& p, const ScalarValue& written, std::string_view what) {
  const long long b = written.as_integer(what);
  const bool standard = b > 0 && b <= 4'000'000 && firmware_iface::SerialTransport::is_supported_baud(static_cast<int>(b));
  if (!standard)
    written.fail("expected a standard serial baud rate (9600, 19200, 38400, 57600, 115200, 230400, 1000000...), found " +
                 written.describe());
  if (!p.device_accepts_baud(static_cast<int>(b)))
    written.fail("a " + std::string(p.name) + " device cannot run at " + written.describe() +
                 " baud; expected one of: " + p.bauds_text);
  return static_cast<int>(b);
}

std::size_t index_on_link(const rig::Rig& rig, const rig::ActuatorSpec& wanted) {
  std::size_t i = 0;
  for (const rig::ActuatorSpec& a : rig.actuators_on(wanted.link)) {
    if (&a == &wanted) return i;
    ++i;
  }
  return i;
}

}  // namespace avar::assembly
