// avar export --stream: a streaming board's project (project_export.hpp).
#include <algorithm>
#include <stdexcept>

#include "avar/core/input_error.hpp"
#include "avar/device/project_export.hpp"
#include "avar/device/stream_player.hpp"
#include "avar/rig/link_options.hpp"
#include "project_text.hpp"

namespace avar::device {
namespace {

const rig::LinkSpec& stream_link(const rig::Rig& rig) {
  for (const rig::LinkSpec& l : rig.links)
    if (l.protocol == "avar-device") return l;
  throw InputError(SourceLocation{rig.file, 1, 1}, "rig '" + rig.name +
                                                       "' has no avar-device link; --stream exports the board of one "
                                                       "(a link with protocol: avar-device)");
}

std::size_t knot_frame_bytes(std::size_t channels) { return 4 + 4 * channels; }

ExportBudget stream_budget(const Project& p) {
  const DeviceTarget& t = *p.target;
  const std::size_t channels = p.figure.channels.size();
  const auto n = static_cast<std::uint8_t>(channels);  // at most kMaxChannels (figure_from_rig)
  ExportBudget b;
  b.flash = {{"the Arduino core, Serial, Wire and the sketch (estimate)", t.core_flash},
             {"the streaming player, the avar-device protocol and the figure", t.stream_flash},
             {"the figure record", p.figure_record.size()}};
  b.ram = {{"the Arduino core's buffers and the stack (estimate)", t.core_ram},
           {"the player, its frame buffer and an answer",
            t.stream_ram + t.board_ram * p.figure.boards.size() + stream_frame_room(n) + stream_reply_room(n)},
           {std::to_string(channels) + " channels", channels * t.stream_channel_ram},
           {std::to_string(p.stream_settings.knots) + " knot frames (the link's device_knots)",
            p.stream_settings.knots * knot_frame_bytes(channels)}};
  for (const BudgetItem& i : b.flash) b.flash_used += i.bytes;
  for (const BudgetItem& i : b.ram) b.ram_used += i.bytes;
  b.flash_size = t.flash;
  b.ram_size = t.ram;
  b.data_used = p.figure_record.size();
  b.data_limit = t.data_limit;
  return b;
}

std::string outputs_text(const Project& p) {
  std::string text;
  for (std::size_t c = 0; c < p.figure.channels.size(); ++c) {
    const FigureChannelSpec& ch = p.figure.channels[c];
    text += "//   " + std::to_string(c) + "  " + ch.name + ": PCA9685 " + hex_byte(p.figure.boards[ch.board].address) +
            " output " + std::to_string(ch.output) + "\n";
  }
  return text;
}

std::string stream_header(const Project& p) {
  const StreamSettings& s = p.stream_settings;
  std::string h = "#pragma once\n// Written by avar export --stream from rig '" + p.figure.rig + "' (link '" + s.link +
                  "') for " + std::string(p.target->name) + ": the streaming board's figure. Do not edit; export again.\n";
  h += "#include <stdint.h>\n\n#include \"avar/device/figure.hpp\"\n\n";
  h += "#define AVAR_CHANNEL_COUNT " + std::to_string(p.figure.channels.size()) + "\n";
  h += "#define AVAR_BOARD_COUNT " + std::to_string(p.figure.boards.size()) + "\n";
  h += "#define AVAR_RATE_HZ " + std::to_string(p.figure.rate) + "\n";
  h += "// Knot frames held (the link's device_knots) and the link silence that eases to rest.\n";
  h += "#define AVAR_KNOTS " + std::to_string(s.knots) + "\n";
  h += "#define AVAR_WATCHDOG_US " + std::to_string(s.watchdog_us) + "UL\n";
  h += "// What avar sends (the link's knot_ms and lead_ms): for --verify's stream.\n";
  h += "#define AVAR_KNOT_US " + std::to_string(s.knot_us) + "UL\n";
  h += "#define AVAR_LEAD_US " + std::to_string(s.lead_us) + "UL\n";
  h += "#ifndef AVAR_SERIAL_BAUD\n#define AVAR_SERIAL_BAUD " + std::to_string(s.baud) + "\n#endif\n\n";
  h += "namespace avar_stream {\n\nextern const uint8_t kFigure[" + std::to_string(p.figure_record.size()) +
       "];\n\n}  // namespace avar_stream\n";
  return h;
}

std::string stream_source(const Project& p) {
  std::string s = "// Written by avar export --stream: the figure record (docs: reference/device-engine).\n";
  s += "#include \"avar_stream.h\"\n\nnamespace avar_stream {\n\n";
  s += "// " + std::to_string(p.figure.channels.size()) + " channels at " + std::to_string(p.figure.rate) + " Hz:\n" +
       outputs_text(p);
  s += "extern const uint8_t kFigure[" + std::to_string(p.figure_record.size()) + "] AVAR_DEVICE_FLASH = {" +
       byte_array(p.figure_record) + "};\n\n}  // namespace avar_stream\n";
  return s;
}

std::string stream_sketch(const Project& p) {
  const StreamSettings& st = p.stream_settings;
  std::string boards;
  for (const FigureBoardSpec& b : p.figure.boards) boards += (boards.empty() ? "" : ", ") + hex_byte(b.address);
  std::string s =
      "// " + p.figure.rig + "'s streaming board on " + std::string(p.target->boards) + ", exported by avar export --stream.\n";
  s += "// avar plays the figure through this board: the rig's link '" + st.link +
       "' (protocol avar-device) is this board's\n// USB serial port, at " + std::to_string(st.baud) +
       " baud. Nothing else may print on it.\n";
  s += "// Wiring: PCA9685 board(s) at " + boards + " (outputs 0-15 each) on I2C (" + std::string(p.target->i2c_pins) +
       ");\n// the servos' own 5-6 V supply on the board's power terminal, grounds joined.\n";
  s += "// Link outputs (the rig's output: keys):\n" + outputs_text(p);
  s += "\n#include <avar_stream_figure.h>\n\nvoid setup() { avar_stream_figure::begin(); }\n\n"
       "void loop() { avar_stream_figure::run(); }\n";
  return s;
}

}  // namespace

Project export_stream_project(const rig::Rig& rig, const DeviceTarget& target, const ExportOptions& options) {
  if (target.host())
    throw std::invalid_argument(
        "--stream: a Linux host needs no streaming board; avar itself drives PCA9685 boards on "
        "/dev/i2c-N (a link of protocol pca9685)");
  const rig::LinkSpec& link = stream_link(rig);
  const auto& o = link.options_as<rig::AvarDeviceOptions>();
  Project p;
  p.stream = true;
  p.target = &target;
  p.figure = stream_figure_from_rig(rig);
  p.library_name = options.library_name.empty() ? "avar_" + identifier(rig.name) + "_stream" : options.library_name;
  p.figure_record = encode_figure_record(p.figure);
  p.stream_settings.link = link.name;
  p.stream_settings.baud = static_cast<long>(link.baud);
  p.stream_settings.knots = static_cast<std::uint32_t>(o.device_knots);
  p.stream_settings.watchdog_us = static_cast<std::uint32_t>(o.device_watchdog_ms) * 1000u;
  p.stream_settings.knot_us = static_cast<std::uint32_t>(o.knot_ms) * 1000u;
  p.stream_settings.lead_us = static_cast<std::uint32_t>(o.lead_ms) * 1000u;
  p.budget = stream_budget(p);
  if (!p.budget.fits())
    throw InputError(link.where, "the streaming board of link '" + link.name + "' does not fit the " + std::string(target.name) +
                                     " (" + std::string(target.boards) + "):\n" + describe_budget(p.budget) +
                                     "(fewer knot frames, device_knots, or a board with more RAM)");
  add_library_files(p, options, "avar_stream_figure.h",
                    "The streaming board of " + p.figure.rig + ": plays the curve knots avar sends over serial.",
                    "Exported by avar export --stream for " + std::string(target.name) + " (" + std::string(target.boards) +
                        "). " + std::to_string(p.figure.channels.size()) + " servos on PCA9685 boards.");
  add_source_files(p);
  p.files.push_back({"src/avar_stream.h", stream_header(p)});
  p.files.push_back({"src/avar_stream.cpp", stream_source(p)});
  p.files.push_back({"examples/" + p.library_name + "/" + p.library_name + ".ino", stream_sketch(p)});
  return p;
}

}  // namespace avar::device
