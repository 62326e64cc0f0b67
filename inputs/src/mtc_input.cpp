#include <rtmidi/RtMidi.h>

#include <mutex>
#include <stdexcept>
#include <vector>

#include "avar/inputs/atomic_input_counters.hpp"
#include "avar/inputs/midi_input.hpp"
#include "avar/inputs/mtc_decoder.hpp"
#include "avar/inputs/timecode_inputs.hpp"

namespace avar::inputs {

struct MtcInput::Device {
  std::unique_ptr<RtMidiIn> in;
  MtcDecoder decoder;
  TimecodeMailbox* mailbox = nullptr;
  AtomicTimecodeCounters* counters = nullptr;
  std::mutex errors_mutex;
  std::string last_error;
};

namespace {

void mtc_record_error(RtMidiError::Type type, const std::string& text, void* user) {
  if (type == RtMidiError::WARNING || type == RtMidiError::DEBUG_WARNING) return;
  auto* device = static_cast<MtcInput::Device*>(user);
  const std::lock_guard lock(device->errors_mutex);
  device->last_error = text;
}

void mtc_throw_if_failed(MtcInput::Device& device, const std::string& what) {
  const std::lock_guard lock(device.errors_mutex);
  if (device.last_error.empty()) return;
  throw std::runtime_error("MTC: " + what + ": " + device.last_error);
}

void on_mtc_message(double /*delta_seconds*/, std::vector<unsigned char>* message, void* user) {
  const std::int64_t arrived = input_arrival_now_ns();
  auto* device = static_cast<MtcInput::Device*>(user);
  TimecodeFix fix;
  switch (device->decoder.decode(*message, fix)) {
    case MtcVerdict::fix:
      device->mailbox->publish(fix, arrived);
      AtomicTimecodeCounters::bump(device->counters->fixes);
      return;
    case MtcVerdict::partial: AtomicTimecodeCounters::bump(device->counters->partial); return;
    case MtcVerdict::not_timecode: AtomicTimecodeCounters::bump(device->counters->ignored); return;
    case MtcVerdict::malformed: AtomicTimecodeCounters::bump(device->counters->bad); return;
  }
}

}  // namespace

MtcInput::MtcInput(std::string port) : wanted_(std::move(port)) {}

MtcInput::~MtcInput() { stop(); }

void MtcInput::start() {
  if (device_) return;
  if (const std::string missing = midi_input_missing(); !missing.empty())
    throw std::runtime_error("MTC input '" + wanted_ + "': " + missing);
  auto device = std::make_unique<Device>();
  device->mailbox = &mailbox_;
  device->counters = &counters_;
  try {
    device->in = std::make_unique<RtMidiIn>(RtMidi::LINUX_ALSA, "avar timecode");
  } catch (const RtMidiError& e) {
    throw std::runtime_error("MTC: cannot open the ALSA sequencer: " + e.getMessage());
  }
  device->in->setErrorCallback(&mtc_record_error, device.get());
  std::vector<std::string> ports;
  const unsigned count = device->in->getPortCount();
  for (unsigned i = 0; i < count; ++i) ports.push_back(device->in->getPortName(i));
  mtc_throw_if_failed(*device, "listing the input ports");
  const std::size_t index = select_midi_port(wanted_, ports);
  // Time code is what we want: SysEx (full frames) and MIDI time messages pass.
  device->in->ignoreTypes(/*midiSysex=*/false, /*midiTime=*/false, /*midiSense=*/true);
  device->in->setCallback(&on_mtc_message, device.get());
  device->in->openPort(static_cast<unsigned>(index), "avar timecode");
  mtc_throw_if_failed(*device, "opening '" + ports[index] + "'");
  opened_ = ports[index];
  device_ = std::move(device);
}

void MtcInput::stop() noexcept {
  if (!device_) return;
  device_->in->closePort();  // joins RtMidi's input thread
  device_.reset();
}

std::string MtcInput::describe() const { return "MIDI Time Code from '" + (opened_.empty() ? wanted_ : opened_) + "'"; }

}  // namespace avar::inputs
