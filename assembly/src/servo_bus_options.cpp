#include "avar/assembly/servo_bus_options.hpp"

#include <vector>

#include "avar/firmware_iface/device_watch.hpp"

namespace avar::assembly {

ServoBusOptions servo_bus_options(const rig::LinkSpec& link, std::initializer_list<std::string_view> extra_keys) {
  const rig::LinkSettings& s = link.settings;
  std::vector<std::string_view> keys(extra_keys);
  for (std::string_view k : {"readback", "reply_timeout_ms", "retries"}) keys.push_back(k);
  s.expect_only_keys(keys);
  ServoBusOptions bus;
  if (const ScalarValue* r = s.find("readback")) {
    const std::string mode = r->as_string("readback");
    if (mode == "none") bus.readback = Readback::none;
    else if (mode == "position") bus.readback = Readback::position;
    else if (mode == "full") bus.readback = Readback::full;
    else r->fail("unknown readback " + r->describe() + "; expected one of: none, position, full");
  }
  if (const ScalarValue* t = s.find("reply_timeout_ms")) {
    const long long ms = t->as_integer("reply_timeout_ms");
    if (ms < 1 || ms > 1000) t->fail("expected reply_timeout_ms from 1 to 1000, found " + t->describe());
    bus.reply_timeout_ms = static_cast<int>(ms);
  }
  if (const ScalarValue* r = s.find("retries")) {
    const long long n = r->as_integer("retries");
    if (n < 0 || n > 10) r->fail("expected retries from 0 to 10, found " + r->describe());
    bus.retries = static_cast<int>(n);
  }
  return bus;
}

std::uint32_t silent_exchanges(const rig::Rig& rig, std::size_t link) {
  return firmware_iface::silence_budget(rig.links[link].watchdog_s, rig.rate_hz);
}

}  // namespace avar::assembly
