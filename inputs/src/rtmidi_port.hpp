#pragma once
// One RtMidi input port on the ALSA sequencer, chosen by number or name (select_midi_port), for
// every input that reads MIDI: controls (midi_input.cpp) and MIDI Time Code (mtc_input.cpp).
// Private to the inputs library: RtMidi stays out of the public headers.
//
// RtMidi reports through its error callback once one is set, and returns instead of throwing:
// errors are recorded there and thrown here as std::runtime_error; warnings are kept, never
// printed.
//
// Threads: constructed and destroyed on one thread; RtMidi's ALSA thread calls the message
// callback from openPort until the destructor has closed the port. warnings() from any thread.

#include <rtmidi/RtMidi.h>

#include <memory>
#include <mutex>
#include <string>
#include <string_view>

namespace avar::inputs {

struct RtMidiPortOptions {
  const char* label;                 ///< names the input in errors: "MIDI" ("MIDI input 'x': ...")
  const char* client;                ///< our ALSA sequencer client's name
  const char* port;                  ///< our input port's name
  bool pass_sysex_and_time = false;  ///< let SysEx and MIDI time messages through (timecode wants them)
};

class RtMidiPort {
 public:
  /// Opens the port `wanted` names and calls `callback(delta, message, user)` on RtMidi's thread
  /// for every message it lets through. Throws std::runtime_error when there is no ALSA sequencer
  /// (or no permission on it), when no port or several ports match (the message lists them), or
  /// when ALSA refuses. Not real-time.
  RtMidiPort(std::string_view wanted, const RtMidiPortOptions& options, RtMidiIn::RtMidiCallback callback, void* user);
  /// Closes the port: joins RtMidi's input thread, so no callback runs after it returns.
  ~RtMidiPort();
  RtMidiPort(const RtMidiPort&) = delete;
  RtMidiPort& operator=(const RtMidiPort&) = delete;

  /// The full name of the port opened.
  const std::string& opened() const noexcept { return opened_; }
  /// RtMidi's warnings since opening, one a line.
  std::string warnings() const;

  struct Errors {
    mutable std::mutex mutex;
    std::string last_error;  ///< the last error RtMidi reported, "" when none since thrown
    std::string warnings;
  };

 private:
  /// Throws what RtMidi reported during `what`, if anything, and forgets it.
  void throw_if_failed(const std::string& what);

  std::string label_;
  Errors errors_;  // before in_: RtMidi's error callback writes here until in_ is gone
  std::unique_ptr<RtMidiIn> in_;
  std::string opened_;
};

}  // namespace avar::inputs
