#pragma once
// A MIDI input port (a controller's knobs, faders, keys and pads) as named controls, read through
// the ALSA sequencer with RtMidi. Controls are named as in midi_decoder.hpp ("ch1.cc7",
// "ch10.note36", "ch1.bend"). System exclusive, timing and active sensing are filtered out by
// RtMidi before they reach the decoder.
//
// Threads: RtMidi's ALSA thread decodes each message and posts it, stamped with CLOCK_MONOTONIC
// at its arrival in the callback. start/stop/describe from one thread; counters() from any.

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "avar/inputs/atomic_input_counters.hpp"
#include "avar/inputs/input_source.hpp"
#include "avar/inputs/midi_decoder.hpp"

namespace avar::inputs {

/// Why MIDI input cannot work on this machine ("no ALSA sequencer on this machine (/dev/snd/seq
/// absent)"), or "" when it can.
std::string midi_input_missing();

/// The index of the port `wanted` names among `ports`: a port number ("1"), or a case-insensitive
/// substring of one port's name ("nano"); a whole name, matched without regard to case, wins
/// over substrings. Throws std::runtime_error listing the ports when none or several match.
std::size_t select_midi_port(std::string_view wanted, std::span<const std::string> ports);

class MidiInput final : public InputSource {
 public:
  /// `port` as select_midi_port takes it. Opens nothing yet.
  explicit MidiInput(std::string port, MidiDecoderConfig config = {});
  ~MidiInput() override;
  MidiInput(const MidiInput&) = delete;
  MidiInput& operator=(const MidiInput&) = delete;

  /// Opens the port and delivers its controls into `sink`. Throws std::runtime_error when there is
  /// no ALSA sequencer, no port or several ports match (the message lists the ports), or ALSA
  /// refuses. A second start() while running is a no-op with the same sink and throws
  /// std::logic_error with another. Not real-time.
  void start(ControlSink& sink) override;
  void stop() noexcept override;
  /// "MIDI 'nanoKONTROL2:nanoKONTROL2 MIDI 1 20:0'" once open; "MIDI 'nano'" before.
  std::string describe() const override;
  InputCounters counters() const noexcept override { return counters_.snapshot(); }

  /// RtMidi's warnings since start(), until stop() (its error callback records them instead of
  /// printing them to stderr).
  std::string warnings() const;

  struct Device;  ///< the RtMidiIn and what its callback needs

 private:
  std::string wanted_;
  std::string opened_;
  MidiDecoderConfig config_;
  AtomicInputCounters counters_;
  std::unique_ptr<Device> device_;
};

}  // namespace avar::inputs
