// `avar export`: the bundled PCA9685 head exported for an Uno (files written, the budget printed),
// and the refusals: an unknown target, a rig whose servos are not on PCA9685 boards, a trigger
// naming no show. Nothing is written on an error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

using testing::run_avar;

const std::string kExportHeadShow = AVAR_SOURCE_DIR "/examples/shows/hello-head.yaml";
const std::string kExportHeadRig = AVAR_SOURCE_DIR "/examples/rigs/pca9685-head.yaml";

TEST(ExportCommand, ExportsTheBundledHeadForAnUno) {
  const std::string dir = testing::temp_path("avar_pca9685_head");
  std::filesystem::remove_all(dir);
  const auto r = run_avar(
      {"export", kExportHeadShow, "--rig", kExportHeadRig, "--target", "atmega328p", "--out", dir, "--boot", "hello-head"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_NE(r.out.find("library avar_pca9685_head for atmega328p"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("8 channels at 50 Hz on 1 PCA9685 board(s), I2C on SDA A4, SCL A5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("flash "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("RAM "), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/library.properties"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/examples/avar_pca9685_head/avar_pca9685_head.ino"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/src/avar/device/curve_engine.cpp"));
  std::filesystem::remove_all(dir);
}

bool installed(const std::string& program) { return std::system(("command -v " + program + " > /dev/null 2>&1").c_str()) == 0; }

/// The exported library's sources that fail to compile as the Arduino IDE compiles a library for
/// an Uno (every .cpp under src/, gnu++11, against the Arduino API's declarations), warnings as
/// errors; and the example sketch.
std::vector<std::string> not_compiling_for_an_uno(const std::string& dir, const std::string& sketch) {
  const std::string compile = "avr-g++ -mmcu=atmega328p -std=gnu++11 -fsyntax-only -Wall -Wextra -Werror -I" +
                              std::string(AVAR_TEST_DATA_DIR) + "/arduino_api -I" + dir + "/src ";
  std::vector<std::string> failed;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir + "/src"))
    if (entry.path().extension() == ".cpp" && std::system((compile + entry.path().string()).c_str()) != 0)
      failed.push_back(entry.path().string());
  if (std::system((compile + "-x c++ " + dir + "/examples/" + sketch + "/" + sketch + ".ino").c_str()) != 0)
    failed.push_back(sketch + ".ino");
  return failed;
}

// The bundled example of the standalone guide: hello-head on an Uno with a PCA9685 board, proved
// under simavr (and on a Pico-class Cortex-M0+ under QEMU): every control tick's I2C bytes and
// outputs equal the host build's.
TEST(ExportCommand, VerifyProvesTheExportUnderTheEmulators) {
  for (const std::string target : {"atmega328p", "cortex-m0plus"}) {
    const bool avr = target == "atmega328p";
    if (!installed(avr ? "avr-g++" : "arm-none-eabi-g++") || !installed(avr ? "simavr" : "qemu-system-arm"))
      GTEST_SKIP() << "the " << target << "'s compiler or emulator is not installed (scripts/install-deps.sh installs them)";
    const std::string dir = testing::temp_path("avar_verify_" + target);
    std::filesystem::remove_all(dir);
    const auto r = run_avar({"export", kExportHeadShow, "--rig", kExportHeadRig, "--target", target, "--out", dir, "--verify",
                             "--name", "avar_verify_" + target, "--button", "2", "--idle", "1"});
    EXPECT_EQ(r.code, kExitOk) << r.out << r.err;
    EXPECT_NE(r.out.find(target + ": 4824 samples, 0 mismatches"), std::string::npos) << r.out << r.err;
    if (avr) {
      EXPECT_EQ(not_compiling_for_an_uno(dir, "avar_verify_atmega328p"), std::vector<std::string>{});
    }
    std::filesystem::remove_all(dir);
  }
}

const std::string kPinRig = AVAR_SOURCE_DIR "/examples/rigs/pin-servo-head.yaml";

// Hobby servos on the board's own pins: every control tick's pulse (the microseconds handed to the
// Servo library, which it turns into its timer's compare value) equals the host build's under
// simavr and QEMU, and the library compiles for an Uno with the Servo API.
TEST(ExportCommand, VerifyProvesServosOnPinsUnderTheEmulators) {
  for (const std::string target : {"atmega328p", "cortex-m3"}) {
    const bool avr = target == "atmega328p";
    if (!installed(avr ? "avr-g++" : "arm-none-eabi-g++") || !installed(avr ? "simavr" : "qemu-system-arm"))
      GTEST_SKIP() << "the " << target << "'s compiler or emulator is not installed (scripts/install-deps.sh installs them)";
    const std::string dir = testing::temp_path("avar_pins_" + target);
    std::filesystem::remove_all(dir);
    const auto r = run_avar({"export", kExportHeadShow, "--rig", kPinRig, "--target", target, "--out", dir, "--verify"});
    EXPECT_EQ(r.code, kExitOk) << r.out << r.err;
    EXPECT_NE(r.out.find("8 channels at 50 Hz on 8 servos on pins 2, 3, 4, 5, 6, 7, 8, 9"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(target + ": 4824 samples, 0 mismatches"), std::string::npos) << r.out << r.err;
    if (avr) {
      EXPECT_EQ(not_compiling_for_an_uno(dir, "avar_pin_servo_head"), std::vector<std::string>{});
      std::ifstream sketch(dir + "/examples/avar_pin_servo_head/avar_pin_servo_head.ino");
      const std::string text{std::istreambuf_iterator<char>(sketch), std::istreambuf_iterator<char>()};
      EXPECT_NE(text.find("signal wire on its pin (2, 3, 4, 5, 6, 7, 8, 9)"), std::string::npos) << text;
    }
    std::filesystem::remove_all(dir);
  }
}

TEST(ExportCommand, PinsATargetCannotDriveAreRefusedWithTheReason) {
  std::ifstream file(kPinRig);
  const std::string rig{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  const auto refused = [&](const std::string& from, const std::string& to, const std::string& target) {
    std::string text = rig;
    text.replace(text.find(from), from.size(), to);
    const std::string path = testing::write_temp_file("pins.yaml", text);
    const std::string dir = testing::temp_path("out");
    return run_avar({"export", kExportHeadShow, "--rig", path, "--target", target, "--out", dir});
  };
  const auto serial = refused("pin: 2,", "pin: 1,", "atmega328p");
  EXPECT_EQ(serial.code, kExitBadInput);
  EXPECT_NE(serial.err.find("pin 1 carries Serial (the commands) on the atmega328p"), std::string::npos) << serial.err;
  const auto absent = refused("pin: 2,", "pin: 20,", "atmega328p");
  EXPECT_NE(absent.err.find("pin 20 is not a pin of the atmega328p (pins 0 to 19)"), std::string::npos) << absent.err;
  EXPECT_EQ(refused("pin: 2,", "pin: 20,", "atmega2560").code, kExitOk) << "a Mega has pin 20";
  const auto many = refused("pin: 2,", "pin: 2,", "esp32c3");
  EXPECT_NE(many.err.find("8 servos on pins; the esp32c3's Servo library drives at most 6"), std::string::npos) << many.err;
  const auto host = refused("pin: 2,", "pin: 2,", "host");
  EXPECT_NE(host.err.find("a Linux machine drives pin servos with avar play and its pwm link"), std::string::npos) << host.err;
  const auto rate = refused("pwm: {frequency: 50}", "pwm: {frequency: 100}", "atmega328p");
  EXPECT_NE(rate.err.find("the boards' Servo libraries send 50"), std::string::npos) << rate.err;
  const auto wide = refused("min_us: 1200, max_us: 1650", "min_us: 500, max_us: 1650", "atmega328p");
  EXPECT_NE(wide.err.find("a pin servo's pulses lie within 544 to 2400 us"), std::string::npos) << wide.err;
}

const std::string kStreamRig = AVAR_SOURCE_DIR "/examples/rigs/streaming-head.yaml";

// A streaming board, proved as a show-playing one is: one scripted stream of avar-device frames
// (damage, silence past the watchdog, stops, releases, avar's clock starting over) through the
// host build and the emulated one, every tick's I2C bytes, outputs and answers compared.
TEST(ExportCommand, VerifyProvesAStreamingBoardUnderTheEmulators) {
  for (const std::string target : {"atmega328p", "cortex-m3"}) {
    const bool avr = target == "atmega328p";
    if (!installed(avr ? "avr-g++" : "arm-none-eabi-g++") || !installed(avr ? "simavr" : "qemu-system-arm"))
      GTEST_SKIP() << "the " << target << "'s compiler or emulator is not installed (scripts/install-deps.sh installs them)";
    const std::string dir = testing::temp_path("avar_stream_verify_" + target);
    std::filesystem::remove_all(dir);
    const auto r = run_avar({"export", "--stream", "--rig", kStreamRig, "--target", target, "--out", dir, "--verify"});
    EXPECT_EQ(r.code, kExitOk) << r.out << r.err;
    EXPECT_NE(r.out.find("streaming board of link 'head': 8 channels at 200 Hz"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(target + ": 41600 samples, 0 mismatches (5200 control ticks of a scripted stream"), std::string::npos)
        << r.out << r.err;
    if (avr) {
      EXPECT_EQ(not_compiling_for_an_uno(dir, "avar_streaming_head_stream"), std::vector<std::string>{});
    }
    std::filesystem::remove_all(dir);
  }
}

TEST(ExportCommand, AStreamingBoardTakesNoShowsOrTriggers) {
  const std::string dir = testing::temp_path("avar_stream_refused");
  std::filesystem::remove_all(dir);
  auto r = run_avar({"export", kExportHeadShow, "--stream", "--rig", kStreamRig, "--target", "atmega328p", "--out", dir});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("export it without shows"), std::string::npos) << r.err;
  r = run_avar({"export", "--stream", "--rig", kStreamRig, "--target", "atmega328p", "--out", dir, "--boot", "1"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--boot: a streaming board has no shows"), std::string::npos) << r.err;
  r = run_avar({"export", "--stream", "--rig", kStreamRig, "--target", "atmega328p", "--out", dir, "--baud", "9600"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--baud: a streaming board's serial port runs at its avar-device link's baud"), std::string::npos)
      << r.err;
  r = run_avar({"export", "--stream", "--rig", kExportHeadRig, "--target", "atmega328p", "--out", dir});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("has no avar-device link"), std::string::npos) << r.err;
  r = run_avar({"export", "--rig", kExportHeadRig, "--target", "atmega328p", "--out", dir});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("expected at least one show file (or --stream)"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// The host target: the same figure and shows as a Linux program (a Raspberry Pi with PCA9685
// boards on /dev/i2c-N), built by the project's own CMakeLists.txt; its --trace shows the boards'
// start-up and the show's writes on simulated time, and it ends at rest.
TEST(ExportCommand, ExportsAProgramForALinuxHost) {
  const std::string dir = testing::temp_path("avar_export_host");
  std::filesystem::remove_all(dir);
  const auto r = run_avar({"export", kExportHeadShow, "--rig", kExportHeadRig, "--target", "host", "--out", dir});
  ASSERT_EQ(r.code, kExitOk) << r.out << r.err;
  EXPECT_NE(r.out.find("program avar_pca9685_head for host"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("program: cmake -S " + dir), std::string::npos) << r.out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/src/avar_figure.cpp")) << "no Arduino glue";
  const std::string build = dir + "/build";
  ASSERT_EQ(std::system(("cmake -S " + dir + " -B " + build + " > /dev/null && cmake --build " + build + " > /dev/null").c_str()),
            0);
  const std::string trace = dir + "/trace.txt";
  ASSERT_EQ(std::system((build + "/avar_pca9685_head --trace --play 1 < /dev/null > " + trace).c_str()), 0);
  std::ifstream in(trace);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_GT(lines.size(), 100u);
  // The PCA9685 start-up: asleep with auto-increment, the prescale for 50 Hz, totem-pole outputs,
  // awake, the oscillator's 500 us, restart.
  const std::vector<std::string> start = {"i2c 0x40: 00 31", "i2c 0x40: fe 79", "i2c 0x40: 01 04",
                                          "i2c 0x40: 00 21", "wait 500 us",     "i2c 0x40: 00 a1"};
  EXPECT_EQ(std::vector<std::string>(lines.begin(), lines.begin() + 6), start);
  EXPECT_NE(std::system((build + "/avar_pca9685_head --bus " + dir + "/no-such-bus < /dev/null 2> /dev/null").c_str()), 0);
  std::filesystem::remove_all(dir);

  auto refused =
      run_avar({"export", kExportHeadShow, "--rig", kExportHeadRig, "--target", "host", "--out", dir, "--button", "2"});
  EXPECT_EQ(refused.code, kExitBadInput);
  EXPECT_NE(refused.err.find("--button: a Linux host has no button pin"), std::string::npos) << refused.err;
  refused = run_avar({"export", "--stream", "--rig", kStreamRig, "--target", "host", "--out", dir});
  EXPECT_EQ(refused.code, kExitBadInput);
  EXPECT_NE(refused.err.find("a Linux host needs no streaming board"), std::string::npos) << refused.err;
  std::filesystem::remove_all(dir);
}

TEST(ExportCommand, RefusesWhatItCannotExportAndWritesNothing) {
  const std::string dir = testing::temp_path("avar_export_refused");
  std::filesystem::remove_all(dir);
  auto r = run_avar({"export", kExportHeadShow, "--rig", kExportHeadRig, "--target", "atmega8", "--out", dir});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--target: found 'atmega8'; expected one of atmega328p, atmega2560, cortex-m0plus"), std::string::npos)
      << r.err;
  r = run_avar({"export", kExportHeadShow, "--rig", AVAR_SOURCE_DIR "/examples/rigs/hello-head.yaml", "--target", "atmega328p",
                "--out", dir});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("hello-head.yaml:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("PCA9685"), std::string::npos) << r.err;
  r = run_avar({"export", kExportHeadShow, "--rig", kExportHeadRig, "--target", "atmega328p", "--out", dir, "--idle", "3"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_NE(r.err.find("--idle: found '3'; expected a show's name or number (1 to 1): hello-head"), std::string::npos) << r.err;
  r = run_avar({"export", kExportHeadShow, "--rig", kExportHeadRig, "--target", "atmega328p", "--out", dir, "--button", "x"});
  EXPECT_EQ(r.code, kExitBadInput);
  EXPECT_FALSE(std::filesystem::exists(dir));
}

}  // namespace
}  // namespace avar::app
