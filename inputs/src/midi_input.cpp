#include "avar/inputs/midi_input.hpp"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <stdexcept>
#include <vector>

#include "avar/core/monotonic_clock.hpp"
#include "rtmidi_port.hpp"

namespace avar::inputs {

struct MidiInput::Device {
  ControlSink* sink = nullptr;
  AtomicInputCounters* counters = nullptr;
  MidiDecoder decoder;
  std::unique_ptr<RtMidiPort> port;  // last: closed first, before what its callback uses
};

namespace {

constexpr const char* kSequencerDevice = "/dev/snd/seq";

std::string lowercase(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

std::string port_list(std::span<const std::string> ports) {
  if (ports.empty()) return "none";
  std::string list;
  for (std::size_t i = 0; i < ports.size(); ++i) {
    if (i > 0) list += ", ";
    list += std::to_string(i) + ": '" + ports[i] + "'";
  }
  return list;
}

void on_midi_message(double /*delta_seconds*/, std::vector<unsigned char>* message, void* user) {
  const std::int64_t arrived = monotonic_ns();
  auto* device = static_cast<MidiInput::Device*>(user);
  MidiControl control;
  const bool moved = device->decoder.decode(*message, &control);
  device->counters->add(InputCounters{1, moved ? 0u : 1u});
  if (moved) device->sink->post(control.name(), control.value, control.bipolar, arrived);
}

}  // namespace

std::string midi_input_missing() {
  if (::access(kSequencerDevice, R_OK | W_OK) == 0) return "";
  if (::access(kSequencerDevice, F_OK) == 0)
    return "no permission on the ALSA sequencer (/dev/snd/seq): add yourself to the 'audio' group";
  return "no ALSA sequencer on this machine (/dev/snd/seq absent; `sudo modprobe snd-seq` loads it)";
}

std::size_t select_midi_port(std::string_view wanted, std::span<const std::string> ports) {
  std::size_t number = 0;
  const auto [end, error] = std::from_chars(wanted.data(), wanted.data() + wanted.size(), number);
  if (!wanted.empty() && error == std::errc{} && end == wanted.data() + wanted.size()) {
    if (number < ports.size()) return number;
    throw std::runtime_error("no MIDI input port number " + std::string(wanted) + " (ports: " + port_list(ports) + ")");
  }
  const std::string needle = lowercase(wanted);
  std::vector<std::size_t> matches;
  for (std::size_t i = 0; i < ports.size(); ++i) {
    const std::string name = lowercase(ports[i]);
    if (name == needle) return i;
    if (name.find(needle) != std::string::npos) matches.push_back(i);
  }
  if (matches.size() == 1) return matches.front();
  if (matches.empty())
    throw std::runtime_error("no MIDI input port matching '" + std::string(wanted) + "' (ports: " + port_list(ports) + ")");
  std::string several;
  for (const std::size_t i : matches) several += (several.empty() ? "'" : ", '") + ports[i] + "'";
  throw std::runtime_error("MIDI input '" + std::string(wanted) + "' matches several ports (" + several +
                           "): give more of the name, or the port number (ports: " + port_list(ports) + ")");
}

MidiInput::MidiInput(std::string port, MidiDecoderConfig config) : wanted_(std::move(port)), config_(config) {}

MidiInput::~MidiInput() { stop(); }

void MidiInput::start(ControlSink& sink) {
  if (device_) {
    if (device_->sink == &sink) return;
    throw std::logic_error("MIDI input " + describe() + " already delivers into another sink");
  }
  auto device = std::make_unique<Device>();
  device->sink = &sink;
  device->counters = &counters_;
  device->decoder = MidiDecoder(config_);
  device->port = std::make_unique<RtMidiPort>(wanted_, RtMidiPortOptions{"MIDI", "avar", "avar input", false}, &on_midi_message,
                                              device.get());
  opened_ = device->port->opened();
  device_ = std::move(device);
}

void MidiInput::stop() noexcept {
  if (!device_) return;
  device_->port.reset();  // joins RtMidi's input thread: no callback after this
  device_.reset();
}

std::string MidiInput::describe() const { return "MIDI '" + (opened_.empty() ? wanted_ : opened_) + "'"; }

std::string MidiInput::warnings() const {
  if (!device_) return "";
  return device_->port->warnings();
}

}  // namespace avar::inputs
