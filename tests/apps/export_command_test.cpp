// `avar export`: the bundled PCA9685 head exported for an Uno (files written, the budget printed),
// and the refusals: an unknown target, a rig whose servos are not on PCA9685 boards, a trigger
// naming no show. Nothing is written on an error.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

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
  EXPECT_NE(r.out.find("8 channels at 50 Hz on 1 PCA9685 board(s); I2C on SDA A4, SCL A5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("flash "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("RAM "), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/library.properties"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/examples/avar_pca9685_head/avar_pca9685_head.ino"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/src/avar/device/curve_engine.cpp"));
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
