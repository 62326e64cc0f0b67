#pragma once
// avar export: shows and a rig as a ready microcontroller project. An Arduino library
// (library.properties, src/, examples/) that PlatformIO also reads (library.json): the device
// engine's sources as avar built them, the figure and the shows as data in flash, and a sketch
// wired from the rig. Before anything is written the export adds up what the target needs and
// refuses, naming the figures, a project that would not fit its flash or RAM.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "avar/device/device_target.hpp"
#include "avar/device/figure_export.hpp"
#include "avar/device/show_export.hpp"
#include "avar/playback/runtime/show.hpp"

namespace avar::device {

/// What triggers a show on the device (indices into the exported shows; -1: none).
struct ExportTriggers {
  int boot_show = -1;   ///< started at power-up, after the soft start
  int idle_show = -1;   ///< played (looping, if the show loops) whenever nothing else plays
  int button_pin = -1;  ///< a pin (to ground, pulled up) whose press starts button_show
  int button_show = 0;
  long serial_baud = 115200;  ///< serial commands: '1'..'9' start a show, 's' stops
};

struct ExportOptions {
  std::string library_name;  ///< "" for avar_<rig>
  std::string version = "0.1.0";
  /// library.properties' url (a required field): where the library's project lives; "" for a
  /// file URL of the library's own name.
  std::string url;
  ExportTriggers triggers;
};

/// One line of a budget: what takes the bytes.
struct BudgetItem {
  std::string what;
  std::size_t bytes = 0;
};

/// What the project needs of its target.
struct ExportBudget {
  std::vector<BudgetItem> flash, ram;
  std::size_t flash_used = 0, flash_size = 0, ram_used = 0, ram_size = 0;
  std::size_t data_used = 0, data_limit = 0;  ///< shows and figure, read in place
  bool fits() const noexcept { return flash_used <= flash_size && ram_used <= ram_size && data_used <= data_limit; }
};

/// One exported show.
struct ExportedShow {
  std::string name;
  ShowImage image;
};

struct ProjectFile {
  std::string path;  ///< relative to the project directory
  std::string text;
};

/// A streaming board's settings, from the rig's avar-device link (avar export --stream).
struct StreamSettings {
  std::string link;                ///< the link's name
  long baud = 115200;              ///< the serial port's
  std::uint32_t knots = 16;        ///< knot frames the board holds
  std::uint32_t watchdog_us = 0;   ///< link silence that eases it to rest
  std::uint32_t knot_us = 50000;   ///< avar's knot spacing (the verification's stream)
  std::uint32_t lead_us = 150000;  ///< how far ahead avar sends a knot
};

struct Project {
  std::string library_name;
  const DeviceTarget* target = nullptr;
  FigureSpec figure;
  std::vector<std::uint8_t> figure_record;
  std::vector<ExportedShow> shows;
  std::uint8_t features = 0;  ///< kFeature* the shows use (the engine is built with only these)
  /// The engine's 32-bit fast path is in (left out only where the project would not fit with it).
  bool fast = true;
  ExportBudget budget;
  std::vector<ProjectFile> files;
  /// A streaming board (no shows: it plays what avar streams to it), with its settings.
  bool stream = false;
  StreamSettings stream_settings;
};

/// The project for `shows` on `rig`'s figure for `target`. Every show is encoded for the figure's
/// channels (a channel a show has no track for holds its rest pose; tracks of channels the device
/// does not drive are left out). Throws InputError for what the device cannot play or drive, and
/// for a project that does not fit its target (the message gives the budget). The fast path is
/// left out, and the budget says so, when that makes the project fit.
Project export_project(const rig::Rig& rig, const std::vector<playback::Show>& shows, const DeviceTarget& target,
                       const ExportOptions& options = {});

/// The project of a streaming board for `rig`'s avar-device link on `target` (avar export
/// --stream): the streaming player, the avar-device protocol and the figure record (the link's
/// outputs on PCA9685 boards, stream_figure_from_rig), the board holding the link's device_knots
/// knot frames and easing to rest after its device_watchdog_ms, its serial port at the link's baud.
/// Throws InputError for a rig without such a link and for a project that does not fit (the
/// message gives the budget).
Project export_stream_project(const rig::Rig& rig, const DeviceTarget& target, const ExportOptions& options = {});

/// The 0-based index of the show `text` names among `shows`: by its name, or by its number 1..N;
/// -1 for an empty text. Throws std::invalid_argument "found 'X'; expected a show's name or number
/// (1 to N): names".
int exported_show_index(const std::string& text, const std::vector<playback::Show>& shows);

/// Writes the project's files under `directory` (created; files of the same names are replaced).
void write_project(const Project& project, const std::filesystem::path& directory);

/// The budget as a table: "flash  21,412 of 32,256 bytes (66 %)" and its items.
std::string describe_budget(const ExportBudget& budget);
/// Where a project's figure puts its servos: "1 PCA9685 board(s), I2C on SDA A4, SCL A5", "8 servos
/// on pins 2, 3, 4, 5, 6, 7, 8, 9", or both joined by "; ".
std::string describe_outputs(const Project& project);

}  // namespace avar::device
