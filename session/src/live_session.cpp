#include "avar/session/live_session.hpp"

#include <ostream>

#include "avar/inputs/input_source_factory.hpp"

namespace avar::session {

LiveSession::LiveSession(const rig::Rig& rig, const config::InputMap& map, const std::vector<std::string>& uris)
    : inputs_(config::live_channels(rig), map.mappings, config::live_effectors(rig)) {
  for (const std::string& uri : uris) sources_.push_back(inputs::make_input_source(uri));
  try {
    for (auto& source : sources_) source->start(inputs_.sink());
  } catch (...) {
    stop();
    throw;
  }
}

LiveSession::~LiveSession() { stop(); }

void LiveSession::stop() noexcept {
  for (auto& source : sources_) source->stop();
}

void LiveSession::describe(std::ostream& out) const {
  for (const auto& source : sources_) {
    const inputs::InputCounters k = source->counters();
    out << "  input " << source->describe() << ": " << k.messages << " messages, " << k.ignored << " ignored\n";
  }
  if (const std::uint64_t unknown = inputs_.mailbox().unknown(); unknown > 0)
    out << "  " << unknown << " messages for controls no mapping uses (see `avar inputs monitor`)\n";
}

}  // namespace avar::session
