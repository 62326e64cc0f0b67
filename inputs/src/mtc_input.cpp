#include <stdexcept>
#include <vector>

#include "avar/core/monotonic_clock.hpp"
#include "avar/inputs/atomic_input_counters.hpp"
#include "avar/inputs/midi_input.hpp"
#include "avar/inputs/mtc_decoder.hpp"
#include "avar/inputs/timecode_inputs.hpp"
#include "rtmidi_port.hpp"

namespace avar::inputs {

struct MtcInput::Device {
  MtcDecoder decoder;
  TimecodeMailbox* mailbox = nullptr;
  AtomicTimecodeCounters* counters = nullptr;
  std::unique_ptr<RtMidiPort> port;  // last: closed first, before what its callback uses
};

namespace {

void on_mtc_message(double /*delta_seconds*/, std::vector<unsigned char>* message, void* user) {
  const std::int64_t arrived = monotonic_ns();
  auto* device = static_cast<MtcInput::Device*>(user);
  TimecodeFix fix;
  switch (device->decoder.decode(*message, fix)) {
    case MtcVerdict::fix:
      device->mailbox->publish(fix, arrived);
      device->counters->add(&TimecodeCounters::fixes);
      return;
    case MtcVerdict::partial: device->counters->add(&TimecodeCounters::partial); return;
    case MtcVerdict::not_timecode: device->counters->add(&TimecodeCounters::ignored); return;
    case MtcVerdict::malformed: device->counters->add(&TimecodeCounters::bad); return;
  }
}

}  // namespace

MtcInput::MtcInput(std::string port) : wanted_(std::move(port)) {}

MtcInput::~MtcInput() { stop(); }

void MtcInput::start() {
  if (device_) return;
  auto device = std::make_unique<Device>();
  device->mailbox = &mailbox_;
  device->counters = &counters_;
  // Time code is what we want: SysEx (full frames) and MIDI time messages pass.
  device->port = std::make_unique<RtMidiPort>(wanted_, RtMidiPortOptions{"MTC", "avar timecode", "avar timecode", true},
                                              &on_mtc_message, device.get());
  opened_ = device->port->opened();
  device_ = std::move(device);
}

void MtcInput::stop() noexcept {
  if (!device_) return;
  device_->port.reset();  // joins RtMidi's input thread
  device_.reset();
}

std::string MtcInput::describe() const { return "MIDI Time Code from '" + (opened_.empty() ? wanted_ : opened_) + "'"; }

}  // namespace avar::inputs
