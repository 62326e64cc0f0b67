#include "avar/assembly/sim_offer.hpp"

#include <cerrno>
#include <cstdlib>

#include "avar/assembly/can_drive.hpp"
#include "avar/assembly/protocol.hpp"

namespace avar::assembly {

const char* to_string(SimTransport t) noexcept {
  switch (t) {
    case SimTransport::pty: return "a pseudo-terminal";
    case SimTransport::udp_loopback: return "UDP on 127.0.0.1";
    case SimTransport::in_process: return "inside the avar process that drives it";
  }
  return "unknown";
}

const std::string& SimValues::text(const std::string& name) const {
  static const std::string none;
  const auto it = values_.find(name);
  return it == values_.end() ? none : it->second;
}

namespace {

long long whole_number(const std::string& name, const std::string& text) {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0) throw SimOptionError("--" + name + ": '" + text + "' is not a whole number");
  return v;
}

}  // namespace

long long SimValues::integer(const std::string& name) const { return whole_number(name, text(name)); }

std::vector<long long> SimValues::integers(const std::string& name) const {
  std::vector<long long> out;
  const std::string& all = text(name);
  std::size_t from = 0;
  while (from <= all.size()) {
    const std::size_t comma = all.find(',', from);
    const std::size_t to = comma == std::string::npos ? all.size() : comma;
    out.push_back(whole_number(name, all.substr(from, to - from)));
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  return out;
}

bool SimValues::flag(const std::string& name) const {
  const std::string& v = text(name);
  return !v.empty() && v != "false";
}

std::vector<const SimOffer*> sim_offers() {
  std::vector<const SimOffer*> out;
  for (const Protocol* p : protocols()) out.push_back(&p->sim);
  for (const CanDriveProtocol* d : can_drive_protocols()) out.push_back(&d->sim);
  return out;
}

std::string sim_offer_help(const SimOffer& offer) {
  std::string text = std::string(offer.description) + "\n\nServed on: " + to_string(offer.transport);
  switch (offer.transport) {
    case SimTransport::pty:
      text += " (the default; --pty says so). Prints the pseudo-terminal's path on stdout (one line), then serves until Ctrl-C.";
      break;
    case SimTransport::udp_loopback: text += ". Prints its HOST:PORT on stdout (one line), then serves until Ctrl-C."; break;
    case SimTransport::in_process: text += "; `avar sim " + std::string(offer.name) + "` only explains how."; break;
  }
  return text + "\n\nExample:\n" + offer.example + "\n";
}

}  // namespace avar::assembly
