#include "rtmidi_port.hpp"

#include <stdexcept>
#include <vector>

#include "avar/inputs/midi_input.hpp"

namespace avar::inputs {

namespace {

void record_rtmidi_error(RtMidiError::Type type, const std::string& text, void* user) {
  auto* errors = static_cast<RtMidiPort::Errors*>(user);
  const std::lock_guard lock(errors->mutex);
  if (type == RtMidiError::WARNING || type == RtMidiError::DEBUG_WARNING) errors->warnings += text + "\n";
  else errors->last_error = text;
}

}  // namespace

RtMidiPort::RtMidiPort(std::string_view wanted, const RtMidiPortOptions& options, RtMidiIn::RtMidiCallback callback, void* user)
    : label_(options.label) {
  // RtMidi prints to stderr before it throws when the sequencer is missing: ask first.
  if (const std::string missing = midi_input_missing(); !missing.empty())
    throw std::runtime_error(label_ + " input '" + std::string(wanted) + "': " + missing);
  try {
    in_ = std::make_unique<RtMidiIn>(RtMidi::LINUX_ALSA, options.client);
  } catch (const RtMidiError& e) {
    throw std::runtime_error(label_ + ": cannot open the ALSA sequencer: " + e.getMessage());
  }
  if (in_->getCurrentApi() != RtMidi::LINUX_ALSA)
    throw std::runtime_error(label_ + ": this RtMidi was built without ALSA support");
  in_->setErrorCallback(&record_rtmidi_error, &errors_);

  std::vector<std::string> ports;
  const unsigned count = in_->getPortCount();
  throw_if_failed("listing the input ports");
  for (unsigned i = 0; i < count; ++i) ports.push_back(in_->getPortName(i));
  throw_if_failed("listing the input ports");
  const std::size_t index = select_midi_port(wanted, ports);

  const bool filter = !options.pass_sysex_and_time;
  in_->ignoreTypes(/*midiSysex=*/filter, /*midiTime=*/filter, /*midiSense=*/true);
  in_->setCallback(callback, user);
  in_->openPort(static_cast<unsigned>(index), options.port);
  throw_if_failed("opening '" + ports[index] + "'");
  opened_ = ports[index];
}

RtMidiPort::~RtMidiPort() { in_->closePort(); }

std::string RtMidiPort::warnings() const {
  const std::lock_guard lock(errors_.mutex);
  return errors_.warnings;
}

void RtMidiPort::throw_if_failed(const std::string& what) {
  const std::lock_guard lock(errors_.mutex);
  if (errors_.last_error.empty()) return;
  const std::string error = errors_.last_error;
  errors_.last_error.clear();
  throw std::runtime_error(label_ + ": " + what + ": " + error);
}

}  // namespace avar::inputs
