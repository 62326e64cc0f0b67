#include "avar/export_command.hpp"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <ostream>
#include <stdexcept>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/core/format.hpp"
#include "avar/device/export_verify.hpp"
#include "avar/device/project_export.hpp"
#include "avar/exit_codes.hpp"
#include "avar/option_error.hpp"

namespace avar::app {
namespace {

/// exported_show_index, its refusal reported at the option.
int show_index(const std::string& text, const std::vector<playback::Show>& shows, const std::string& option) {
  try {
    return device::exported_show_index(text, shows);
  } catch (const std::invalid_argument& e) {
    throw option_error(option, e.what());
  }
}

/// The budget and the sketch's path, then the verification when asked.
int finish(const device::Project& project, const ExportOptions& o, std::ostream& out) {
  const device::DeviceTarget& target = *project.target;
  out << device::describe_budget(project.budget);
  if (target.host())
    out << "program: cmake -S " << o.out_dir << " -B " << o.out_dir << "/build && cmake --build " << o.out_dir << "/build, then "
        << o.out_dir << "/build/" << project.library_name << " --help\n";
  else out << "sketch: examples/" << project.library_name << "/" << project.library_name << ".ino\n";
  if (!o.verify) return kExitOk;
  const device::ExportVerification v = device::verify_export(project, o.out_dir, out);
  out << target.name << ": " << v.samples << " samples, " << v.mismatches << " mismatches (" << v.ticks
      << (project.stream ? " control ticks of a scripted stream, " : " control ticks of every show, ")
      << format_number(std::round(v.emulator_seconds * 10) / 10) << " s under " << v.emulator << "); the build: " << v.flash_bytes
      << " bytes of flash, " << v.ram_bytes << " of RAM without the Arduino core\n";
  for (const std::string& d : v.differing) out << "  host | " << target.name << ": " << d << "\n";
  return v.mismatches == 0 && v.differing.empty() ? kExitOk : kExitFault;
}

int run_stream_export(const ExportOptions& o, const device::DeviceTarget& target, std::ostream& out) {
  const rig::Rig rig = config::load_rig_file(o.rig_path);
  device::ExportOptions options;
  options.library_name = o.name;
  options.url = "file://" + std::filesystem::absolute(o.out_dir).lexically_normal().string();
  const device::Project project = device::export_stream_project(rig, target, options);
  device::write_project(project, o.out_dir);
  const device::StreamSettings& s = project.stream_settings;
  out << "wrote " << o.out_dir << ": library " << project.library_name << " for " << target.name << " (" << target.boards << "), "
      << project.files.size() << " files\n";
  out << "streaming board of link '" << s.link << "': " << project.figure.channels.size() << " channels at "
      << project.figure.rate << " Hz on " << project.figure.boards.size() << " PCA9685 board(s); I2C on " << target.i2c_pins
      << "; serial at " << s.baud << " baud; " << s.knots << " knot frames; to rest after " << s.watchdog_us / 1000
      << " ms of silence\n";
  return finish(project, o, out);
}

}  // namespace

CLI::App* add_export_subcommand(CLI::App& app, ExportOptions& o) {
  CLI::App* cmd =
      app.add_subcommand("export", "Write a microcontroller project (Arduino / PlatformIO library) that plays shows standalone");
  cmd->add_option("shows", o.show_paths, "Show files (YAML), at most 9: played by serial commands 1..9 (none with --stream)");
  cmd->add_option("--rig", o.rig_path,
                  "Rig file: its channels on PCA9685 links and on one pwm link (the board's pins) are the device's figure")
      ->required();
  cmd->add_option("--target", o.target, "Microcontroller: " + device::device_target_names())->required();
  cmd->add_option("--out", o.out_dir, "Directory to write the library into (an Arduino libraries/ folder's entry)")->required();
  cmd->add_option("--name", o.name, "Library name (default avar_RIG)");
  cmd->add_option("--boot", o.boot, "Show (name or number) to play at power-up, after the soft start");
  cmd->add_option("--idle", o.idle, "Show to play whenever nothing else plays");
  cmd->add_option("--button", o.button, "PIN[:SHOW]: a button from PIN to ground plays SHOW (default the first)");
  cmd->add_option("--baud", o.baud, "Serial commands' baud rate (default 115200)")->check(CLI::Range(300L, 2000000L));
  cmd->add_flag("--stream", o.stream,
                "Instead of shows: the board of the rig's avar-device link, which plays the curve knots avar streams "
                "to it over serial");
  cmd->add_flag("--verify", o.verify,
                "Then build the project for the host and the target, run it under the target's emulator (simavr, "
                "QEMU) and compare every tick");
  std::string targets;
  for (const device::DeviceTarget& t : device::device_targets())
    targets += "  " + std::string(t.name) + std::string(16 - std::min<std::size_t>(15, t.name.size()), ' ') +
               std::string(t.boards) + "\n";
  cmd->footer("Targets:\n" + targets +
              "The figure is the rig's channels with an actuator; each must be a hobby servo on a PCA9685 board\n"
              "(a pca9685 link) or on one of the board's own pins (one pwm link: pin is the board's pin number,\n"
              "pulses 544 to 2400 us at 50 Hz, driven by the core's Servo library). Every show is encoded for\n"
              "the device engine (a channel a show has no track for holds its rest pose); the project carries\n"
              "the engine's sources with only the features the shows use, the figure and shows as data in\n"
              "flash, and an example sketch wired from the rig. The export\n"
              "adds up flash and RAM for the target first and refuses, with the figures, what does not fit.\n"
              "On the board: the channels' limits apply, servos glide from rest at power-up and ease to rest on\n"
              "stop; serial commands '1'..'9' play a show, 's' stops.\n"
              "With --stream: no shows; the board of the rig's avar-device link, which plays the knots avar streams\n"
              "(its serial port at the link's baud, the link's device_knots and device_watchdog_ms).\n"
              "Examples:\n"
              "  avar export examples/shows/hello-head.yaml --rig examples/rigs/pca9685-head.yaml \\\n"
              "      --target atmega328p --out ~/Arduino/libraries/avar_pca9685_head\n"
              "      then in the Arduino IDE: File > Examples > avar_pca9685_head, upload to an Uno\n"
              "  avar export intro.yaml scare.yaml --rig prop.yaml --target cortex-m0plus --out prop \\\n"
              "      --idle intro --button 15:scare\n"
              "      a Pico that loops intro and plays scare when the button on GP15 is pressed\n"
              "  avar export SHOW --rig RIG --target atmega328p --out DIR --verify\n"
              "      and prove it: the project built for the host and for the Uno, run under simavr, every\n"
              "      control tick's I2C bytes and outputs compared: 'atmega328p: N samples, 0 mismatches'\n"
              "  avar export --stream --rig examples/rigs/streaming-head.yaml --target atmega328p \\\n"
              "      --out ~/Arduino/libraries/avar_streaming_head_stream --verify\n"
              "      a board that avar streams to (the rig's avar-device link): upload it, give its port\n"
              "      in the link, and every show plays through it; --verify drives both builds with one\n"
              "      scripted stream (damage, silence, stops, releases) and compares every tick");
  return cmd;
}

int run_export(const ExportOptions& o, std::ostream& out, std::ostream& err) {
  try {
    const device::DeviceTarget* target = device::find_device_target(o.target);
    if (target == nullptr)
      throw option_error("--target", "found '" + o.target + "'; expected one of " + device::device_target_names());
    if (o.stream) {
      if (!o.show_paths.empty())
        throw option_error("--stream", "found show " + o.show_paths.front() +
                                           "; a streaming board plays what avar streams to it: export it without shows");
      for (const auto& [given, name] :
           {std::pair{!o.boot.empty(), "--boot"}, std::pair{!o.idle.empty(), "--idle"}, std::pair{!o.button.empty(), "--button"}})
        if (given) throw option_error(name, "a streaming board has no shows of its own to trigger; leave it out with --stream");
      if (o.baud != 0)
        throw option_error("--baud",
                           "a streaming board's serial port runs at its avar-device link's baud in the rig; "
                           "set it there, not with --stream");
      return run_stream_export(o, *target, out);
    }
    if (o.show_paths.empty()) throw option_error("shows", "expected at least one show file (or --stream)");
    const rig::Rig rig = config::load_rig_file(o.rig_path);
    std::vector<playback::Show> shows;
    for (const std::string& path : o.show_paths) shows.push_back(config::load_show_file(path));
    device::ExportOptions options;
    options.library_name = o.name;
    options.url = "file://" + std::filesystem::absolute(o.out_dir).lexically_normal().string();
    options.triggers.boot_show = show_index(o.boot, shows, "--boot");
    options.triggers.idle_show = show_index(o.idle, shows, "--idle");
    options.triggers.serial_baud = o.baud == 0 ? 115200 : o.baud;
    if (!o.button.empty()) {
      const std::size_t colon = o.button.find(':');
      const std::string pin = o.button.substr(0, colon);
      int number = -1;
      const auto [end, ec] = std::from_chars(pin.data(), pin.data() + pin.size(), number);
      if (ec != std::errc() || end != pin.data() + pin.size() || number < 0 || number > 255)
        throw option_error("--button", "found '" + o.button + "'; expected PIN or PIN:SHOW with PIN a number 0 to 255");
      options.triggers.button_pin = number;
      options.triggers.button_show = colon == std::string::npos ? 0 : show_index(o.button.substr(colon + 1), shows, "--button");
    }
    const device::Project project = device::export_project(rig, shows, *target, options);
    device::write_project(project, o.out_dir);
    out << "wrote " << o.out_dir << (target->host() ? ": program " : ": library ") << project.library_name << " for "
        << target->name << " (" << target->boards << "), " << project.files.size() << " files\n";
    out << "figure: " << project.figure.channels.size() << " channels at " << project.figure.rate << " Hz on "
        << device::describe_outputs(project) << "\n";
    for (std::size_t s = 0; s < project.shows.size(); ++s) {
      const device::ShowImage& image = project.shows[s].image;
      out << "show " << s + 1 << ": " << project.shows[s].name << ", " << image.keys << " keys in " << image.bytes.size()
          << " bytes ("
          << format_number(static_cast<double>(image.key_bytes) / static_cast<double>(std::max<std::size_t>(1, image.keys)))
          << " bytes per key)\n";
    }
    return finish(project, o, out);
  } catch (const InputError& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  } catch (const std::runtime_error& e) {  // a missing tool, a failed build or run (and file errors)
    err << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
}

}  // namespace avar::app
