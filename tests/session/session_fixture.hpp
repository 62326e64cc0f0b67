#pragma once
// A show session on the simulated hello-head figure, and an observer that keeps every record
// (copied: the ring's slots are reused).

#include <cmath>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/session/show_session.hpp"

namespace avar::session::test_support {

inline std::string example(const std::string& path) { return std::string(AVAR_SOURCE_DIR) + "/examples/" + path; }

/// The hello-head rig and show, and its channels by name.
struct HelloHead {
  rig::Rig rig = config::load_rig_file(example("rigs/hello-head.yaml"));
  playback::Show show = config::load_show_file(example("shows/hello-head.yaml"));
  std::size_t channel(const std::string& name) const {
    for (std::size_t c = 0; c < rig.channels.size(); ++c)
      if (rig.channels[c].name == name) return c;
    throw std::invalid_argument(name);
  }
};

/// Every link simulated, on the stepped clock at 50 Hz.
inline SessionConfig stepped_config() {
  SessionConfig config;
  config.rate_hz = 50;
  config.stepped = true;
  config.links.simulate_all = true;
  return config;
}

/// What one record said, kept past the record's life.
struct Kept {
  std::uint64_t tick = 0;
  double now_s = 0;
  control::Phase phase = control::Phase::disabled;
  double show_time_s = 0;
  bool paused = false;
  bool estop = false;
  control::FaultCause fault = control::FaultCause::none;
  std::vector<CommandRecord> commands;
  std::vector<ChannelRecord> channels;
  std::vector<firmware_iface::LinkCounters> links;
};

class KeepAll final : public SessionObserver {
 public:
  void on_tick(const TickRecord& r) override {
    Kept k{r.tick, r.now_s, r.phase, r.show_time_s, r.paused, r.estop, r.fault.cause, {}, {}, {}};
    k.commands.assign(r.commands.begin(), r.commands.begin() + static_cast<std::ptrdiff_t>(r.command_count));
    k.channels.assign(r.channels.begin(), r.channels.end());
    k.links.assign(r.links.begin(), r.links.end());
    const std::lock_guard lock(mutex_);
    kept_.push_back(std::move(k));
  }
  std::vector<Kept> kept() const {
    const std::lock_guard lock(mutex_);
    return kept_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<Kept> kept_;
};

/// Calls `act` with every record (on the stepped loop's thread, between ticks): a script that
/// commands the session as the run goes.
class Script final : public SessionObserver {
 public:
  explicit Script(std::function<void(const TickRecord&)> act) : act_(std::move(act)) {}
  void on_tick(const TickRecord& r) override { act_(r); }

 private:
  std::function<void(const TickRecord&)> act_;
};

/// The largest command step per channel between consecutive records, over [from, to) ticks.
inline double largest_step(const std::vector<Kept>& kept, std::size_t channel) {
  double worst = 0;
  for (std::size_t k = 1; k < kept.size(); ++k)
    worst = std::max(worst, std::abs(kept[k].channels[channel].command - kept[k - 1].channels[channel].command));
  return worst;
}

}  // namespace avar::session::test_support
