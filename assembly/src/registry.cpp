#include "avar/assembly/protocol.hpp"

#include <stdexcept>

#include "avar/assembly/avar_device_protocol.hpp"
#include "avar/assembly/can_protocol.hpp"
#include "avar/assembly/dmx_protocol.hpp"
#include "avar/assembly/dynamixel_protocol.hpp"
#include "avar/assembly/feetech_protocol.hpp"
#include "avar/assembly/gpio_protocol.hpp"
#include "avar/assembly/maestro_protocol.hpp"
#include "avar/assembly/network_dmx_protocol.hpp"
#include "avar/assembly/pca9685_protocol.hpp"
#include "avar/assembly/pwm_protocol.hpp"
#include "avar/assembly/ssc32_protocol.hpp"

namespace avar::assembly {

const std::vector<const Protocol*>& protocols() {
  static const std::vector<const Protocol*> all{&maestro_protocol(), &dynamixel_protocol(),   &feetech_protocol(),
                                                &ssc32_protocol(),   &dmx_protocol(),         &can_protocol(),
                                                &gpio_protocol(),    &artnet_protocol(),      &sacn_protocol(),
                                                &pca9685_protocol(), &avar_device_protocol(), &pwm_protocol()};
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

OpenedLink open_over_bytes(const rig::Rig& rig, std::size_t link, const LinkEndpoint& at,
                           std::unique_ptr<firmware_iface::ActuatorLink> (*make)(const rig::Rig& rig, std::size_t link,
                                                                                 firmware_iface::ByteTransport& transport,
                                                                                 const DriverTuning& tuning)) {
  OpenedLink opened;
  if (at.bytes) {
    opened.driver = make(rig, link, *at.bytes, at.tuning);
  } else {
    opened.serial = std::make_unique<firmware_iface::SerialTransport>(at.port, rig.links[link].baud);
    opened.driver = make(rig, link, *opened.serial, at.tuning);
  }
  return opened;
}

const rig::ProtocolSchema& schema_of(const Protocol& p) {
  if (const rig::ProtocolSchema* schema = rig::find_schema(p.name)) return *schema;
  throw std::invalid_argument(std::string("protocol '") + p.name + "' has no schema");
}

}  // namespace avar::assembly
