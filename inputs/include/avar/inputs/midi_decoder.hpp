#pragma once
// MIDI 1.0 channel voice messages as named controls (pure: no I/O, no clock, no allocation).
//
// Names, with C the MIDI channel 1..16 and N the note or controller number 0..127:
//   ch<C>.cc<N>      control change, value/127 (unipolar 0..1)
//   ch<C>.note<N>    note-on velocity/127; 0 on note-off and on note-on with velocity 0
//   ch<C>.bend       pitch bend, 14 bits centred at 8192: 0 -> -1, 8192 -> 0, 16383 -> 1 (bipolar)
//   ch<C>.pressure   channel pressure (aftertouch), value/127
// With fourteen_bit_cc, controllers 0..31 are the MSB and 32..63 the LSB of 14-bit controls
// named after the MSB (ch1.cc7): an MSB posts (MSB*128)/16383 (the spec: the receiver's LSB
// becomes 0), an LSB posts (MSB*128 + LSB)/16383. Without it every controller is its own 7-bit
// control.
//
// Not controls (decode() returns false): polyphonic key pressure, program change, channel mode
// messages (controllers 120..127), system exclusive, system common and real-time messages (clock,
// start, stop, active sensing), and malformed messages (wrong length, data byte >= 0x80).

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace avar::inputs {

/// One control a MIDI message moved; its name lives in the struct.
struct MidiControl {
  std::array<char, 16> name_buffer{};  ///< longest: "ch16.pressure", "ch16.note127"
  std::uint8_t name_length = 0;
  double value = 0;      ///< 0..1, or -1..1 when bipolar
  bool bipolar = false;  ///< pitch bend only

  std::string_view name() const noexcept { return {name_buffer.data(), name_length}; }
};

struct MidiDecoderConfig {
  /// Pairs controllers 0..31 (MSB) with 32..63 (LSB) into 14-bit controls.
  bool fourteen_bit_cc = false;
};

/// Decodes whole MIDI messages (status byte first, no running status: as RtMidi and the ALSA
/// sequencer deliver them). Keeps the last MSB of each 14-bit controller pair. One thread at a
/// time; real-time safe.
class MidiDecoder {
 public:
  explicit MidiDecoder(MidiDecoderConfig config = {}) noexcept : config_(config) {}

  /// Fills *control and returns true when `message` moves a control; false (and *control
  /// untouched) for messages that are not controls (see above).
  bool decode(std::span<const std::uint8_t> message, MidiControl* control) noexcept;

 private:
  MidiDecoderConfig config_;
  std::array<std::array<std::uint8_t, 32>, 16> msb_{};  ///< [channel][controller 0..31]
};

}  // namespace avar::inputs
