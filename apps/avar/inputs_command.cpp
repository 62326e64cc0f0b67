#include "avar/inputs_command.hpp"

#include <CLI/CLI.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <ostream>
#include <thread>

#include "avar/config/rig_file.hpp"
#include "avar/control/controller.hpp"
#include "avar/core/format.hpp"
#include "avar/exit_codes.hpp"
#include "avar/inputs/input_source_factory.hpp"
#include "avar/interrupts.hpp"

namespace avar::app {
namespace {

/// What the devices sent since the last look, per control: the latest value and the range swept.
struct Moved {
  double value = 0;
  double low = 0, high = 0;
  bool bipolar = false;
  std::uint64_t messages = 0;
  std::int64_t last_ns = 0;
};

/// A sink that any device thread may post to; the command's thread takes what arrived.
class RecordingSink final : public inputs::ControlSink {
 public:
  void post(std::string_view control, double value, bool bipolar, std::int64_t arrived_ns) noexcept override {
    if (!std::isfinite(value)) return;
    try {
      const std::lock_guard lock(mutex_);
      auto [it, fresh] = moved_.try_emplace(std::string(control));
      Moved& m = it->second;
      if (fresh) m.low = m.high = value;
      m.value = value;
      m.low = std::min(m.low, value);
      m.high = std::max(m.high, value);
      m.bipolar = bipolar;
      ++m.messages;
      m.last_ns = arrived_ns;
    } catch (...) {  // out of memory: the message is lost, the device thread carries on
    }
  }
  std::map<std::string, Moved> take() {
    const std::lock_guard lock(mutex_);
    std::map<std::string, Moved> taken;
    taken.swap(moved_);
    return taken;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, Moved> moved_;
};

/// Opens and starts the devices; on failure prints why and returns none.
std::vector<std::unique_ptr<inputs::InputSource>> open_inputs(const std::vector<std::string>& uris, inputs::ControlSink& sink,
                                                              std::ostream& err) {
  std::vector<std::unique_ptr<inputs::InputSource>> sources;
  try {
    for (const std::string& uri : uris) sources.push_back(inputs::make_input_source(uri));
    for (auto& s : sources) {
      s->start(sink);
      err << "listening: " << s->describe() << '\n';
    }
  } catch (const std::exception& e) {
    for (auto& s : sources) s->stop();
    err << "error: " << e.what() << '\n';
    return {};
  }
  return sources;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

InputsCommands add_inputs_subcommands(CLI::App& app, InputsOptions& o) {
  CLI::App* inputs =
      app.add_subcommand("inputs", "See what live input devices send, and learn which control drives which channel");
  inputs->require_subcommand(1);
  inputs->footer(
      "Live inputs are devices that drive channels while a figure plays (avar play/puppet/record --input).\n"
      "Each device delivers named controls with normalised values: sticks, hats and pitch bend -1..1,\n"
      "faders, triggers, buttons and notes 0..1. These commands help set them up:\n"
      "  monitor   print each control as it moves, to learn its name (for the inputs: mappings)\n"
      "  learn     move one control per channel when asked; writes a mappings file for --inputs\n"
      "Devices: osc://HOST:PORT (UDP), midi:NAME (ALSA sequencer port), hid:VID:PID[:SERIAL] (gamepad).\n"
      "Examples:\n"
      "  avar inputs monitor --input hid:054c:09cc\n"
      "  avar inputs learn --rig examples/rigs/hello-head.yaml --input midi:nano --channels jaw,neck_pan --out inputs.yaml");
  const char* input_help =
      "Input device, repeatable: osc://HOST:PORT, midi:NAME, hid:VID:PID[:SERIAL]; NAME=URI prefixes its controls";
  InputsCommands cmds;
  cmds.monitor = inputs->add_subcommand("monitor", "Print every control of the devices as it moves (until Ctrl-C)");
  cmds.monitor->add_option("--input", o.inputs, input_help)->required();
  cmds.monitor->add_option("--duration", o.duration_s, "Stop after this many seconds")->check(CLI::PositiveNumber);
  cmds.monitor->footer(
      "Opens the devices and prints one line per control each time its value changes:\n"
      "  1.25 s  pad.x = -0.4961 (bipolar)\n"
      "seconds since start, the control's name (prefixed by NAME= when given), its value, and its kind:\n"
      "bipolar controls span -1..1 with rest at 0 (sticks, hats, pitch bend), unipolar 0..1 (faders,\n"
      "triggers, buttons, notes). Use the names in the control: keys of a rig's inputs: mappings. At the end\n"
      "(Ctrl-C or --duration) each device prints its counters: messages received and ignored (an OSC\n"
      "address it does not know, MIDI clock or SysEx). A device that cannot be opened exits 2 with the reason\n"
      "(HID and MIDI name the devices they can see). Examples:\n"
      "  avar inputs monitor --input hid:054c:09cc                  # a gamepad: which stick is x, y, z, rz?\n"
      "  avar inputs monitor --input pad=osc://:9000 --duration 30  # then: oscsend localhost 9000 /avar/control/jaw f 0.5");
  cmds.learn = inputs->add_subcommand("learn", "Map controls to channels by moving them, one channel after the other");
  cmds.learn->add_option("--rig", o.rig_path, "Rig file whose channels to learn")->required();
  cmds.learn->add_option("--input", o.inputs, input_help)->required();
  cmds.learn->add_option("--channels", o.channels, "Channels to learn, comma-separated, in order (default: all)")->delimiter(',');
  cmds.learn->add_option("--out", o.out_path, "Inputs file to write (YAML, for --inputs)")->required();
  cmds.learn->add_option("--timeout", o.timeout_s, "Seconds to wait for each channel's control (default 30)")
      ->check(CLI::PositiveNumber);
  cmds.learn->footer(
      "Move each control through most of its travel when asked: the first control to sweep at least half\n"
      "of its range is taken (a control learned already is ignored). The file maps each channel's\n"
      "control over the channel's whole range; edit it to add dead zones, expo, priorities.\n"
      "Example: avar inputs learn --rig RIG --input midi:nanoKONTROL --channels jaw,neck_pan --out inputs.yaml");
  return cmds;
}

int run_inputs_monitor(const InputsOptions& options, std::ostream& out, std::ostream& err) {
  RecordingSink sink;
  auto sources = open_inputs(options.inputs, sink, err);
  if (sources.empty()) return kExitBadInput;
  InterruptCounter interrupts;
  err << "move the controls; Ctrl-C ends" << std::endl;
  const auto start = std::chrono::steady_clock::now();
  while (interrupts.count().load() == 0 && (!options.duration_s || seconds_since(start) < *options.duration_s)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    for (const auto& [name, m] : sink.take())
      out << format_fixed(seconds_since(start), 2) << " s  " << name << " = " << format_fixed(m.value, 4) << " ("
          << (m.bipolar ? "bipolar" : "unipolar") << ")\n"
          << std::flush;
  }
  for (auto& s : sources) {
    s->stop();
    const inputs::InputCounters k = s->counters();
    out << s->describe() << ": " << k.messages << " messages, " << k.ignored << " ignored\n";
  }
  return kExitOk;
}

int run_inputs_learn(const InputsOptions& options, std::ostream& out, std::ostream& err) {
  rig::Rig rig;
  try {
    rig = config::load_rig_file(options.rig_path);
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
  std::vector<std::string> channels = options.channels;
  if (channels.empty())
    for (const rig::ChannelSpec& c : rig.channels) channels.push_back(c.name);
  for (const std::string& c : channels)
    if (!rig.find_channel(c)) {
      err << "error: --channels: unknown channel '" << c << "'; expected one of the rig's channels: " << rig.channel_names()
          << '\n';
      return kExitBadInput;
    }

  RecordingSink sink;
  auto sources = open_inputs(options.inputs, sink, err);
  if (sources.empty()) return kExitBadInput;
  InterruptCounter interrupts;
  std::vector<std::pair<std::string, std::string>> learned;  // channel, control
  for (const std::string& channel : channels) {
    err << "move the control for '" << channel << "' through most of its travel..." << std::endl;
    (void)sink.take();  // what moved before the question does not count
    std::map<std::string, Moved> swept;
    std::string found;
    const auto asked = std::chrono::steady_clock::now();
    while (found.empty() && interrupts.count().load() == 0 && seconds_since(asked) < options.timeout_s) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      for (const auto& [moved_name, m] : sink.take()) {
        const std::string& name = moved_name;  // clang 14 cannot capture a structured binding
        if (std::any_of(learned.begin(), learned.end(), [&](const auto& l) { return l.second == name; })) continue;
        auto [it, fresh] = swept.try_emplace(name, m);
        Moved& s = it->second;
        if (!fresh) {
          s.low = std::min(s.low, m.low);
          s.high = std::max(s.high, m.high);
        }
        // Half the normalised range: 1 of a bipolar control's 2, 0.5 of a unipolar one's 1.
        if (s.high - s.low >= (m.bipolar ? 1.0 : 0.5)) found = name;
      }
    }
    if (found.empty()) {
      err << (interrupts.count().load() ? "stopped" : "error: no control moved far enough for '" + channel + "'")
          << "; nothing written\n";
      for (auto& s : sources) s->stop();
      return interrupts.count().load() ? kExitInterrupted : kExitBadInput;
    }
    err << "  '" << channel << "' <- " << found << std::endl;
    learned.emplace_back(channel, found);
  }
  for (auto& s : sources) s->stop();

  YAML::Emitter y;
  y << YAML::BeginMap << YAML::Key << "inputs" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "devices" << YAML::Value << YAML::Flow << options.inputs;
  y << YAML::Key << "mappings" << YAML::Value << YAML::BeginSeq;
  for (const auto& [channel, control] : learned)
    y << YAML::Flow << YAML::BeginMap << YAML::Key << "control" << YAML::Value << control << YAML::Key << "channel" << YAML::Value
      << channel << YAML::EndMap;
  y << YAML::EndSeq << YAML::EndMap << YAML::EndMap;
  std::ofstream file(options.out_path);
  file << "# learned by avar inputs learn for rig '" << rig.name << "'\n" << y.c_str() << '\n';
  if (!file) {
    err << "error: cannot write " << options.out_path << '\n';
    return kExitBadInput;
  }
  out << "wrote " << options.out_path << " (" << learned.size() << " mappings)\n";
  return kExitOk;
}

}  // namespace avar::app
