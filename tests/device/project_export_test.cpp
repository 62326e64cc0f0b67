// avar export's project: the files an Arduino library needs, the engine built with only what the
// shows use, the budget of each target (the Uno example of the issue: 8 channels, 2 minutes at a key
// per second, must fit), and the refusals: a project too big for its target, a trigger naming no
// show.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "avar/config/rig_file.hpp"
#include "avar/config/show_file.hpp"
#include "avar/device/project_export.hpp"

namespace avar::device {
namespace {

const std::string kExportRig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/pca9685-head.yaml";
const std::string kExportShow = std::string(AVAR_SOURCE_DIR) + "/examples/shows/hello-head.yaml";

const ProjectFile* find_file(const Project& p, const std::string& path) {
  for (const ProjectFile& f : p.files)
    if (f.path == path) return &f;
  return nullptr;
}

/// A show of `seconds` with a Bezier key every second on every channel of the rig: each key moves
/// its channel by up to a sixth of the range (seeded), as animation does.
playback::Show long_show(const rig::Rig& rig, int seconds) {
  std::uint32_t seed = 20261207u;
  const auto next = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<double>(seed >> 8) / 16777216.0;
  };
  playback::Show show;
  show.name = "long";
  show.duration = seconds;
  for (const auto& ch : rig.channels) {
    std::vector<playback::RawKey> keys;
    double value = ch.rest;
    for (int t = 0; t <= seconds; ++t) {
      playback::RawKey k;
      k.time = t;
      value = std::clamp(value + (ch.max - ch.min) * (next() - 0.5) / 3.0, ch.min, ch.max);
      k.value = value;
      k.interpolation = playback::Interpolation::bezier;
      keys.push_back(k);
    }
    playback::RawCurve raw(std::move(keys), {"long.yaml", 1, 1});
    playback::Curve curve = playback::Curve::build(raw);
    show.tracks.push_back({ch.name, std::move(raw), std::move(curve), {}});
  }
  return show;
}

TEST(ProjectExport, WritesAnArduinoLibraryWithTheEnginesSourcesAndTheShowsAsData) {
  const rig::Rig rig = config::load_rig_file(kExportRig);
  const Project p = export_project(rig, {config::load_show_file(kExportShow)}, *find_device_target("atmega328p"));
  EXPECT_EQ(p.library_name, "avar_pca9685_head");
  for (const char* path :
       {"library.properties", "library.json", "src/avar_figure.h", "src/avar_figure.cpp", "src/avar_shows.h",
        "src/avar_shows.cpp", "src/avar/device/curve_engine.cpp", "src/avar/device/player.hpp", "src/avar/device/figure.cpp",
        "src/avar/firmware_iface/pca9685_codec.cpp", "examples/avar_pca9685_head/avar_pca9685_head.ino"})
    EXPECT_NE(find_file(p, path), nullptr) << path;
  const std::string properties = find_file(p, "library.properties")->text;
  EXPECT_NE(properties.find("name=avar_pca9685_head\n"), std::string::npos);
  EXPECT_NE(properties.find("architectures=avr\n"), std::string::npos);
  EXPECT_NE(find_file(p, "library.json")->text.find("\"platforms\": \"atmelavr\""), std::string::npos);
  // hello-head has steps, lines and Beziers only: the engine is built without the rest.
  EXPECT_EQ(p.features, 0);
  EXPECT_TRUE(p.fast);
  const std::string config = find_file(p, "src/avar/device/config.hpp")->text;
  EXPECT_EQ(config.find("#define AVAR_DEVICE_EASINGS 0\n"), config.find("#define AVAR_DEVICE_EASINGS"));
  const std::string sketch = find_file(p, "examples/avar_pca9685_head/avar_pca9685_head.ino")->text;
  EXPECT_NE(sketch.find("PCA9685 at 0x40"), std::string::npos);
  EXPECT_NE(sketch.find("SDA A4, SCL A5"), std::string::npos);
  EXPECT_NE(sketch.find("avar_figure::run()"), std::string::npos);
  const std::string shows = find_file(p, "src/avar_shows.cpp")->text;
  EXPECT_NE(shows.find("AVAR_DEVICE_FLASH"), std::string::npos) << "in program memory on AVR";
  EXPECT_NE(shows.find("0x61, 0x76, 0x64, 0x31"), std::string::npos) << "the show image's magic";
  EXPECT_TRUE(p.budget.fits());
}

TEST(ProjectExport, TheUnoHoldsEightChannelsForTwoMinutesAtAKeyASecond) {
  const rig::Rig rig = config::load_rig_file(kExportRig);
  const Project p = export_project(rig, {long_show(rig, 120)}, *find_device_target("atmega328p"));
  EXPECT_TRUE(p.budget.fits()) << describe_budget(p.budget);
  EXPECT_FALSE(p.fast) << "the 32-bit fast path is left out to fit";
  EXPECT_NE(find_file(p, "src/avar/device/config.hpp")->text.find("#define AVAR_DEVICE_FAST 0\n"), std::string::npos);
  EXPECT_NE(describe_budget(p.budget).find("without its 32-bit fast path, to fit"), std::string::npos);
  EXPECT_LE(p.budget.ram_used, 2048u);
  EXPECT_EQ(p.shows[0].image.keys, 8u * 121u);
  EXPECT_LE(static_cast<double>(p.shows[0].image.key_bytes) / static_cast<double>(p.shows[0].image.keys), 12.0);
}

TEST(ProjectExport, RefusesAProjectThatDoesNotFitWithTheBudget) {
  const rig::Rig rig = config::load_rig_file(kExportRig);
  try {
    export_project(rig, {long_show(rig, 600)}, *find_device_target("atmega328p"));
    FAIL() << "ten minutes of 8 channels on an Uno";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("does not fit the atmega328p"), std::string::npos) << message;
    EXPECT_NE(message.find("flash"), std::string::npos) << message;
    EXPECT_NE(message.find("show long"), std::string::npos) << message;
  }
  // The same show fits a Mega.
  EXPECT_TRUE(export_project(rig, {long_show(rig, 600)}, *find_device_target("atmega2560")).budget.fits());
}

TEST(ProjectExport, TriggersNameExportedShows) {
  const rig::Rig rig = config::load_rig_file(kExportRig);
  const std::vector<playback::Show> shows = {config::load_show_file(kExportShow)};
  ExportOptions o;
  o.triggers.boot_show = 1;
  EXPECT_THROW(export_project(rig, shows, *find_device_target("atmega328p"), o), std::invalid_argument);
  o.triggers.boot_show = 0;
  o.triggers.button_pin = 2;
  const Project p = export_project(rig, shows, *find_device_target("cortex-m0plus"), o);
  const std::string header = find_file(p, "src/avar_shows.h")->text;
  EXPECT_NE(header.find("#define AVAR_BOOT_SHOW 0\n"), std::string::npos);
  EXPECT_NE(header.find("#define AVAR_BUTTON_PIN 2\n"), std::string::npos);
  EXPECT_NE(find_file(p, "library.properties")->text.find("architectures=rp2040\n"), std::string::npos);
}

const std::string kStreamRig = std::string(AVAR_SOURCE_DIR) + "/examples/rigs/streaming-head.yaml";

TEST(ProjectExport, AStreamingBoardCarriesThePlayerTheProtocolAndTheLinksSettings) {
  const rig::Rig rig = config::load_rig_file(kStreamRig);
  const Project p = export_stream_project(rig, *find_device_target("atmega328p"));
  EXPECT_TRUE(p.stream);
  EXPECT_TRUE(p.shows.empty());
  EXPECT_EQ(p.library_name, "avar_streaming_head_stream");
  for (const char* path :
       {"src/avar_stream_figure.h", "src/avar_stream_figure.cpp", "src/avar_stream.h", "src/avar_stream.cpp",
        "src/avar/device/stream_player.cpp", "src/avar/device/stream_figure.cpp", "src/avar/firmware_iface/avar_device_codec.cpp",
        "src/avar/device/limiter.cpp", "examples/avar_streaming_head_stream/avar_streaming_head_stream.ino"})
    EXPECT_NE(find_file(p, path), nullptr) << path;
  EXPECT_EQ(find_file(p, "src/avar_figure.cpp"), nullptr) << "the show player's glue would not compile without shows";
  EXPECT_NE(find_file(p, "library.properties")->text.find("includes=avar_stream_figure.h\n"), std::string::npos);
  const std::string header = find_file(p, "src/avar_stream.h")->text;
  for (const char* line : {"#define AVAR_CHANNEL_COUNT 8\n", "#define AVAR_RATE_HZ 200\n", "#define AVAR_KNOTS 16\n",
                           "#define AVAR_WATCHDOG_US 500000UL\n", "#define AVAR_KNOT_US 50000UL\n",
                           "#define AVAR_LEAD_US 150000UL\n", "#define AVAR_SERIAL_BAUD 115200\n"})
    EXPECT_NE(header.find(line), std::string::npos) << line;
  const std::string sketch = find_file(p, "examples/avar_streaming_head_stream/avar_streaming_head_stream.ino")->text;
  EXPECT_NE(sketch.find("link 'head'"), std::string::npos) << sketch;
  EXPECT_NE(sketch.find("0  jaw: PCA9685 0x40 output 0"), std::string::npos) << sketch;
  EXPECT_NE(sketch.find("avar_stream_figure::run()"), std::string::npos);
  EXPECT_TRUE(p.budget.fits()) << describe_budget(p.budget);
  EXPECT_NE(describe_budget(p.budget).find("576  16 knot frames"), std::string::npos) << describe_budget(p.budget);

  // A show export carries none of the streaming board's files.
  const Project shows =
      export_project(config::load_rig_file(kExportRig), {config::load_show_file(kExportShow)}, *find_device_target("atmega328p"));
  EXPECT_EQ(find_file(shows, "src/avar/device/stream_player.cpp"), nullptr);
  EXPECT_EQ(find_file(shows, "src/avar_stream_figure.cpp"), nullptr);
}

TEST(ProjectExport, AStreamingBoardThatDoesNotFitIsRefusedWithItsKnots) {
  std::ifstream in(kStreamRig);
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string setting = "device_rate: 200,";
  yaml.replace(yaml.find(setting), setting.size(), setting + " device_knots: 40,");
  const rig::Rig big = config::load_rig_text(yaml, "big-knots.yaml");
  try {
    export_stream_project(big, *find_device_target("atmega328p"));
    FAIL() << "40 knot frames of 8 channels on an Uno";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("big-knots.yaml:"), std::string::npos) << message;
    EXPECT_NE(message.find("does not fit the atmega328p"), std::string::npos) << message;
    EXPECT_NE(message.find("40 knot frames"), std::string::npos) << message;
  }
  EXPECT_TRUE(export_stream_project(big, *find_device_target("atmega2560")).budget.fits());
  EXPECT_THROW(export_stream_project(config::load_rig_file(kExportRig), *find_device_target("atmega2560")), InputError)
      << "a rig without an avar-device link";
}

TEST(ProjectExport, WritesItsFilesUnderTheDirectory) {
  const rig::Rig rig = config::load_rig_file(kExportRig);
  const Project p = export_project(rig, {config::load_show_file(kExportShow)}, *find_device_target("atmega2560"));
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / "avar_export_project_test";
  std::filesystem::remove_all(dir);
  write_project(p, dir);
  for (const ProjectFile& f : p.files) {
    std::ifstream in(dir / f.path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), f.text) << f.path;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace avar::device
