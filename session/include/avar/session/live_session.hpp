#pragma once
// The live inputs of one run of play, puppet or record: the rig's control mappings mixed over
// the show (control::LiveInputs) and the input devices that feed them, each on its own thread.

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "avar/config/input_map.hpp"
#include "avar/control/live_inputs.hpp"
#include "avar/inputs/input_source.hpp"
#include "avar/rig/rig.hpp"

namespace avar::session {

class LiveSession {
 public:
  /// Opens and starts every input device (`uris`: osc://HOST:PORT, midi:NAME, hid:VID:PID, each
  /// optionally NAME=...). Throws std::invalid_argument for a URI it cannot read and
  /// std::runtime_error for a device it cannot open, naming it; nothing is left running then.
  LiveSession(const rig::Rig& rig, const config::InputMap& map, const std::vector<std::string>& uris);
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  control::LiveInputs& inputs() noexcept { return inputs_; }
  const control::LiveInputs& inputs() const noexcept { return inputs_; }
  /// Stops every device's thread. Idempotent.
  void stop() noexcept;
  /// One line per device, with its message counters, for the summary.
  void describe(std::ostream& out) const;

 private:
  control::LiveInputs inputs_;
  std::vector<std::unique_ptr<inputs::InputSource>> sources_;
};

}  // namespace avar::session
