#include "avar/device/project_export.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "avar/core/format.hpp"
#include "avar/core/input_error.hpp"
#include "avar/device/show_image.hpp"
#include "project_text.hpp"

namespace avar::device {
namespace {

/// The show with one track per figure channel, in figure order: a channel without a track holds
/// its rest pose. A layered show or one with targets passes through (the encoder refuses it).
playback::Show for_figure(const playback::Show& show, const FigureSpec& figure) {
  if (show.layered() || !show.targets.empty()) return show;
  playback::Show out;
  out.name = show.name;
  out.duration = show.duration;
  out.loop = show.loop;
  out.where = show.where;
  for (const FigureChannelSpec& c : figure.channels) {
    const auto found = std::find_if(show.tracks.begin(), show.tracks.end(), [&](const auto& t) { return t.channel == c.name; });
    if (found != show.tracks.end()) {
      out.tracks.push_back(*found);
      continue;
    }
    playback::RawKey rest;
    rest.value = c.rest;
    rest.interpolation = playback::Interpolation::step;
    playback::RawCurve raw({rest}, show.where);
    playback::Curve curve = playback::Curve::build(raw);
    out.tracks.push_back({c.name, std::move(raw), std::move(curve), show.where});
  }
  return out;
}

std::vector<int> pins_of(const FigureSpec& figure) {
  std::vector<int> pins;
  for (const FigureChannelSpec& c : figure.channels)
    if (c.on_pin) pins.push_back(c.output);
  return pins;
}

/// "2, 3, 4": the pins in channel order (AVAR_PINS; "0" when there are none, for a valid array).
std::string pin_list(const FigureSpec& figure) {
  std::string text;
  for (const int pin : pins_of(figure)) text += (text.empty() ? "" : ", ") + std::to_string(pin);
  return text.empty() ? "0" : text;
}

std::string show_list(const Project& p) {
  std::string text;
  for (std::size_t s = 0; s < p.shows.size(); ++s)
    text += "//   " + std::to_string(s + 1) + "  " + p.shows[s].name + " (" +
            format_number(static_cast<double>(p.shows[s].image.keys)) + " keys, " + with_commas(p.shows[s].image.bytes.size()) +
            " bytes)\n";
  return text;
}

std::string shows_header(const Project& p, const ExportTriggers& t) {
  std::string h = "#pragma once\n// Written by avar export from rig '" + p.figure.rig + "' for " + std::string(p.target->name) +
                  ": the figure and its shows. Do not edit; export again.\n";
  h += "#include <stdint.h>\n\n#include \"avar/device/player.hpp\"\n\n";
  h += "#define AVAR_CHANNEL_COUNT " + std::to_string(p.figure.channels.size()) + "\n";
  h += "#define AVAR_BOARD_COUNT " + std::to_string(p.figure.boards.size()) + "\n";
  h += "#define AVAR_PIN_COUNT " + std::to_string(pins_of(p.figure).size()) + "\n";
  h += "#define AVAR_PINS " + pin_list(p.figure) + "\n";

  h += "#define AVAR_SHOW_COUNT " + std::to_string(p.shows.size()) + "\n";
  h += "#define AVAR_RATE_HZ " + std::to_string(p.figure.rate) + "\n";
  h += "#define AVAR_BOOT_SHOW " + std::to_string(t.boot_show) + "\n";
  h += "#define AVAR_IDLE_SHOW " + std::to_string(t.idle_show) + "\n";
  h += "#define AVAR_BUTTON_PIN " + std::to_string(t.button_pin) + "\n";
  h += "#define AVAR_BUTTON_SHOW " + std::to_string(t.button_show) + "\n";
  h += "#ifndef AVAR_SERIAL_BAUD\n#define AVAR_SERIAL_BAUD " + std::to_string(t.serial_baud) + "\n#endif\n\n";
  h += "namespace avar_shows {\n\n";
  h += "extern const uint8_t kFigure[" + std::to_string(p.figure_record.size()) + "];\n";
  h += "extern const avar::device::PlayerShow kShows[AVAR_SHOW_COUNT];\n\n}  // namespace avar_shows\n";
  return h;
}

std::string shows_source(const Project& p) {
  std::string s = "// Written by avar export: the figure record and the show images (docs: reference/device-engine).\n";
  s += "#include \"avar_shows.h\"\n\nnamespace avar_shows {\n\n";
  s += "// The figure: " + std::to_string(p.figure.channels.size()) + " channels at " + std::to_string(p.figure.rate) + " Hz\n";
  for (const FigureChannelSpec& c : p.figure.channels)
    s += "//   " + c.name + ": " +
         (c.on_pin ? "pin " + std::to_string(c.output)
                   : "board " + hex_byte(p.figure.boards[c.board].address) + " output " + std::to_string(c.output)) +
         ", " + format_number(c.at_low_ns / 1000.0) + " to " + format_number(c.at_high_ns / 1000.0) + " us\n";
  s += "extern const uint8_t kFigure[" + std::to_string(p.figure_record.size()) + "] AVAR_DEVICE_FLASH = {" +
       byte_array(p.figure_record) + "};\n\n";
  s += "// The shows:\n" + show_list(p);
  for (std::size_t i = 0; i < p.shows.size(); ++i)
    s += "const uint8_t kShow" + std::to_string(i) + "[" + std::to_string(p.shows[i].image.bytes.size()) +
         "] AVAR_DEVICE_FLASH = {" + byte_array(p.shows[i].image.bytes) + "};\n";
  s += "\nconst avar::device::PlayerShow kShows[AVAR_SHOW_COUNT] = {\n";
  for (std::size_t i = 0; i < p.shows.size(); ++i)
    s += "    {kShow" + std::to_string(i) + ", sizeof kShow" + std::to_string(i) + "},\n";
  s += "};\n\n}  // namespace avar_shows\n";
  return s;
}

std::string boards_text(const Project& p) {
  std::string text;
  for (const FigureBoardSpec& b : p.figure.boards) {
    text += (text.empty() ? "" : ", ") + std::string("a PCA9685 at ") + hex_byte(b.address) + " (link " + b.link + ", " +
            std::to_string(b.frequency_hz) + " Hz)";
  }
  return text;
}

std::string sketch(const Project& p, const ExportTriggers& t) {
  std::string s = "// " + p.figure.rig + " on " + std::string(p.target->boards) + ", exported by avar export.\n";
  if (!p.figure.boards.empty())
    s += "// Wiring: " + boards_text(p) + " on I2C (" + std::string(p.target->i2c_pins) +
         "); the servos' own 5-6 V supply on the board's\n// power terminal, grounds joined.\n";
  if (p.figure.pin_rate != 0)
    s += "// Wiring: each pin servo's signal wire on its pin (" + pin_list(p.figure) +
         "); the servos' own 5-6 V supply,\n// its ground joined to the board's.\n";
  s += "// Outputs:\n";
  for (const FigureChannelSpec& c : p.figure.channels)
    s += "//   " + std::string(c.on_pin ? "pin " : "") + std::to_string(c.output) + "  " + c.name + "\n";
  s += "// Shows:\n" + show_list(p);
  s += "// Serial monitor at " + std::to_string(t.serial_baud) + " baud: send 1..9 to play a show, s to stop.\n";
  if (t.boot_show >= 0) s += "// At power-up it plays " + p.shows[static_cast<std::size_t>(t.boot_show)].name + ".\n";
  if (t.idle_show >= 0) s += "// Between shows it plays " + p.shows[static_cast<std::size_t>(t.idle_show)].name + ".\n";
  if (t.button_pin >= 0)
    s += "// A button from pin " + std::to_string(t.button_pin) + " to ground plays " +
         p.shows[static_cast<std::size_t>(t.button_show)].name + ".\n";
  s += "\n#include <avar_figure.h>\n\nvoid setup() { avar_figure::begin(); }\n\nvoid loop() { avar_figure::run(); }\n";
  return s;
}

std::string show_list_names(const std::vector<playback::Show>& shows) {
  std::string names;
  for (const playback::Show& s : shows) names += (names.empty() ? "" : ", ") + s.name;
  return names;
}

std::string show_names(const Project& p) {
  std::string names;
  for (const ExportedShow& s : p.shows) names += (names.empty() ? "" : ", ") + s.name;
  return names;
}

/// A Linux program's build: every source of the project and the host's main, C++14.
std::string host_cmake(const Project& p) {
  return "# Written by avar export for a Linux host: the figure " + p.figure.rig +
         " and its shows as a program.\n"
         "#   cmake -S . -B build && cmake --build build && build/" +
         p.library_name +
         " --help\n"
         "cmake_minimum_required(VERSION 3.13)\nproject(" +
         p.library_name + " CXX)\nfile(GLOB_RECURSE sources CONFIGURE_DEPENDS src/*.cpp)\nadd_executable(" + p.library_name +
         " ${sources} host/avar_figure_host.cpp)\ntarget_include_directories(" + p.library_name +
         " PRIVATE src)\nset_target_properties(" + p.library_name +
         " PROPERTIES CXX_STANDARD 14 CXX_STANDARD_REQUIRED ON)\n"
         "if(NOT CMAKE_BUILD_TYPE)\n  set(CMAKE_BUILD_TYPE Release)\nendif()\n";
}

void add_files(Project& p, const ExportOptions& o) {
  if (p.target->host()) {
    add_source_files(p);
    p.files.push_back({"src/avar_shows.h", shows_header(p, o.triggers)});
    p.files.push_back({"src/avar_shows.cpp", shows_source(p)});
    p.files.push_back({"host/avar_figure_host.cpp", embedded_text("host/avar_figure_host.cpp")});
    p.files.push_back({"CMakeLists.txt", host_cmake(p)});
    return;
  }
  add_library_files(p, o, "avar_figure.h", "The figure " + p.figure.rig + " and its shows, played by avar's device engine.",
                    "Exported by avar export for " + std::string(p.target->name) + " (" + std::string(p.target->boards) +
                        "). Shows: " + show_names(p) + ".");
  add_source_files(p);
  p.files.push_back({"src/avar_shows.h", shows_header(p, o.triggers)});
  p.files.push_back({"src/avar_shows.cpp", shows_source(p)});
  p.files.push_back({"examples/" + p.library_name + "/" + p.library_name + ".ino", sketch(p, o.triggers)});
}

/// Every pin servo's pin, refused with the reason where the target cannot drive it.
void check_pins(const Project& p, const ExportTriggers& triggers, const rig::Rig& rig) {
  const DeviceTarget& t = *p.target;
  const std::vector<int> pins = pins_of(p.figure);
  if (pins.empty()) return;
  const auto refuse = [&](const std::string& why) {
    throw InputError(SourceLocation{rig.file, 1, 1}, "rig '" + rig.name + "': " + why);
  };
  if (t.pin_high < 0)
    refuse("the " + std::string(t.name) +
           " target drives PCA9685 boards, not servos on pins; a Linux machine drives pin servos with avar play and its pwm "
           "link");
  if (p.figure.pin_rate != 50)
    refuse("its pwm link sends " + std::to_string(p.figure.pin_rate) +
           " pulses a second; the boards' Servo libraries send 50: give the link frequency: 50");
  if (pins.size() > t.pin_servos)
    refuse(std::to_string(pins.size()) + " servos on pins; the " + std::string(t.name) + "'s Servo library drives at most " +
           std::to_string(t.pin_servos) + " (put the rest on a PCA9685 board)");
  for (const int pin : pins) {
    const std::string which = "pin " + std::to_string(pin);
    if (pin > t.pin_high)
      refuse(which + " is not a pin of the " + std::string(t.name) + " (pins 0 to " + std::to_string(t.pin_high) + ")");
    if (pin == t.serial_pins[0] || pin == t.serial_pins[1])
      refuse(which + " carries Serial (the commands) on the " + std::string(t.name) + "; choose another pin");
    if (!p.figure.boards.empty() && (pin == t.i2c_pin_numbers[0] || pin == t.i2c_pin_numbers[1]))
      refuse(which + " carries I2C to the PCA9685 boards on the " + std::string(t.name) + " (" + std::string(t.i2c_pins) +
             "); choose another pin");
    if (pin == triggers.button_pin) refuse(which + " is the --button pin too; choose another");
  }
}

void check_trigger(int show, std::size_t count, const char* what) {
  if (show < -1 || show >= static_cast<int>(count))
    throw std::invalid_argument(std::string(what) + " names show " + std::to_string(show + 1) + "; the export has " +
                                std::to_string(count) + " show(s)");
}

ExportBudget budget_for(const Project& p) {
  const DeviceTarget& t = *p.target;
  ExportBudget b;
  std::size_t data = p.figure_record.size();
  for (const ExportedShow& s : p.shows) data += s.image.bytes.size();
  b.flash = {{"the Arduino core, Serial, Wire and the sketch (estimate)", t.core_flash},
             {p.fast ? "the device engine and figure" : "the device engine and figure (without its 32-bit fast path, to fit)",
              t.engine_flash_for(p.features, p.fast)},
             {"the figure record", p.figure_record.size()}};
  for (const ExportedShow& s : p.shows) b.flash.push_back({"show " + s.name, s.image.bytes.size()});
  const std::size_t channels = p.figure.channels.size();
  b.ram = {{"the Arduino core's buffers and the stack (estimate)", t.core_ram},
           {"the player", t.figure_ram + t.board_ram * p.figure.boards.size() + t.show_ram * p.shows.size()},
           {std::to_string(channels) + " channels", channels * t.channel_ram_for(p.features)}};
  const std::size_t pins = pins_of(p.figure).size();
  if (pins > 0) {
    b.flash.push_back({"the Servo library and the figure's pin outputs (estimate)", t.servo_flash});
    b.ram.push_back(
        {"the Servo library and " + std::to_string(pins) + " servos (estimate)", t.servo_ram + pins * t.servo_each_ram});
  }
  for (const BudgetItem& i : b.flash) b.flash_used += i.bytes;
  for (const BudgetItem& i : b.ram) b.ram_used += i.bytes;
  b.flash_size = t.flash;
  b.ram_size = t.ram;
  b.data_used = data;
  b.data_limit = t.data_limit;
  return b;
}

}  // namespace

int exported_show_index(const std::string& text, const std::vector<playback::Show>& shows) {
  if (text.empty()) return -1;
  for (std::size_t i = 0; i < shows.size(); ++i)
    if (shows[i].name == text) return static_cast<int>(i);
  int number = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (ec == std::errc() && end == text.data() + text.size() && number >= 1 && number <= static_cast<int>(shows.size()))
    return number - 1;
  throw std::invalid_argument("found '" + text + "'; expected a show's name or number (1 to " + std::to_string(shows.size()) +
                              "): " + show_list_names(shows));
}

std::string describe_budget(const ExportBudget& b) {
  const auto line = [](const char* what, std::size_t used, std::size_t size) {
    return std::string(what) + with_commas(used) + " of " + with_commas(size) + " bytes (" +
           std::to_string(size == 0 ? 0 : (used * 100 + size - 1) / size) + " %)" + (used > size ? ": does not fit" : "") + "\n";
  };
  std::string text = line("flash ", b.flash_used, b.flash_size);
  for (const BudgetItem& i : b.flash)
    if (i.bytes > 0) text += "  " + with_commas(i.bytes) + "  " + i.what + "\n";
  text += line("RAM   ", b.ram_used, b.ram_size);
  for (const BudgetItem& i : b.ram)
    if (i.bytes > 0) text += "  " + with_commas(i.bytes) + "  " + i.what + "\n";
  if (b.data_used > b.data_limit) text += line("data read in place ", b.data_used, b.data_limit);
  return text;
}

std::string describe_outputs(const Project& p) {
  std::string text;
  if (!p.figure.boards.empty())
    text = std::to_string(p.figure.boards.size()) + " PCA9685 board(s), I2C on " + std::string(p.target->i2c_pins);
  if (p.figure.pin_rate != 0)
    text += (text.empty() ? "" : "; ") + std::to_string(pins_of(p.figure).size()) + " servos on pins " + pin_list(p.figure);
  return text;
}

Project export_project(const rig::Rig& rig, const std::vector<playback::Show>& shows, const DeviceTarget& target,
                       const ExportOptions& options) {
  if (shows.empty()) throw std::invalid_argument("no show to export; give at least one");
  if (shows.size() > 9)
    throw std::invalid_argument("expected at most 9 shows (serial commands 1..9), found " + std::to_string(shows.size()));
  check_trigger(options.triggers.boot_show, shows.size(), "--boot");
  check_trigger(options.triggers.idle_show, shows.size(), "--idle");
  if (options.triggers.button_pin >= 0) check_trigger(options.triggers.button_show, shows.size(), "--button");
  if (options.triggers.button_pin >= 0 && target.host())
    throw std::invalid_argument("--button: a Linux host has no button pin here; start shows from standard input or with --play");
  Project p;
  p.target = &target;
  p.figure = figure_from_rig(rig);
  p.library_name = options.library_name.empty() ? "avar_" + identifier(rig.name) : options.library_name;
  p.figure_record = encode_figure_record(p.figure);
  check_pins(p, options.triggers, rig);
  const std::vector<ImageChannel> channels = image_channels(p.figure);
  for (const playback::Show& show : shows) {
    ExportedShow exported{show.name, encode_show_image(for_figure(show, p.figure), channels)};
    ShowHeader header;
    const ImageStatus status =
        check_image(exported.image.bytes.data(), static_cast<std::uint32_t>(exported.image.bytes.size()), header);
    if (status != kImageOk) throw std::logic_error("an exported show image does not check (" + std::to_string(status) + ")");
    p.features |= header.features;
    p.shows.push_back(std::move(exported));
  }
  p.budget = budget_for(p);
  if (!p.budget.fits()) {
    p.fast = false;  // slower samples rather than no project
    const ExportBudget slow = budget_for(p);
    if (slow.fits()) p.budget = slow;
    else p.fast = true;
  }
  if (!p.budget.fits())
    throw InputError(SourceLocation{rig.file, 1, 1}, "the figure '" + rig.name + "' with " + show_names(p) +
                                                         " does not fit the " + std::string(target.name) + " (" +
                                                         std::string(target.boards) + "):\n" + describe_budget(p.budget));
  add_files(p, options);
  return p;
}

void write_project(const Project& project, const std::filesystem::path& directory) {
  for (const ProjectFile& f : project.files) {
    const std::filesystem::path path = directory / f.path;
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary);
    out << f.text;
    if (!out) throw std::runtime_error("cannot write " + path.string());
  }
}

}  // namespace avar::device
