#pragma once
// The take of a recording run (`avar record`): every channel a live control touched, as the
// ticks of the running phase commanded it (after mixing and limits), fitted with keys within a
// tolerance and written as a show file; alone, or merged as a clip on a layer of its own over a
// copy of the show that played. The file is read back and every kept curve checked against
// every tick of the take. Not real-time: after the run.

#include <cstddef>
#include <string>
#include <vector>

#include "avar/control/controller.hpp"
#include "avar/control/live_inputs.hpp"
#include "avar/playback/runtime/show.hpp"
#include "avar/rig/rig.hpp"
#include "avar/session/play_recorder.hpp"

namespace avar::session {

struct TakeOptions {
  std::string path;         ///< the show file to write
  double tolerance = 0.25;  ///< the keys stay this close to every tick's value (channel units)
  bool merge = false;       ///< the show that played with the take on layer 'take'; else the take alone
};

/// One channel of the take as it was read back from the file.
struct TakeTrack {
  std::string channel;
  std::size_t keys = 0;
  double max_error = 0;  ///< the largest distance from a tick's value (channel units)
};

struct TakeReport {
  double duration_s = 0;
  std::size_t ticks = 0;  ///< running ticks in the take
  std::vector<TakeTrack> tracks;
};

/// Fits, writes and reads back the take of a finished run (`recorder` kept its samples,
/// `controller` ran `show` on `rig`, `live` were its live inputs). Throws std::runtime_error
/// "nothing to keep: ...; PATH not written" when the figure never ran or no control moved a
/// channel (nothing is written then), std::invalid_argument for `merge` over a show without end
/// (a live-only run), and the show writer's errors when the file cannot be
/// written.
TakeReport write_take(const TakeOptions& options, const rig::Rig& rig, const playback::Show& show,
                      const control::Controller& controller, const PlayRecorder& recorder, const control::LiveInputs& live);

}  // namespace avar::session
