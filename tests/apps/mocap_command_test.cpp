// `avar mocap info|joints`: the joint tree and the joint-position CSV of a BVH fixture whose
// positions were worked by hand (tests/mocap/bvh_reader_test.cpp), and refusals with exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_run.hpp"
#include "../support/csv_rows.hpp"
#include "../support/temp_file.hpp"
#include "avar/exit_codes.hpp"

namespace avar::app {
namespace {

const std::string kMocapArm = AVAR_SOURCE_DIR "/tests/data/mocap/zxy_arm.bvh";

TEST(MocapCommand, InfoPrintsTheTreeChannelsFramesAndRate) {
  const testing::CliResult r = testing::run_avar({"mocap", "info", kMocapArm});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(r.out, kMocapArm +
                       ": BVH\n"
                       "joints: 2 (+1 End Sites)\n"
                       "  Hips  [Xposition Yposition Zposition Zrotation Xrotation Yrotation]\n"
                       "    Elbow  [Zrotation Xrotation Yrotation]\n"
                       "      Elbow_end  (End Site)\n"
                       "frames: 4\n"
                       "frame time: 0.04 s (25 fps)\n"
                       "duration: 0.12 s\n");
}

TEST(MocapCommand, JointsWritesEveryJointEveryFrameInTheFilesAxes) {
  const std::string csv = testing::temp_path("joints.csv");
  const testing::CliResult r = testing::run_avar({"mocap", "joints", kMocapArm, "--out", csv});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  std::ifstream in(csv);
  const auto rows = testing::csv_rows(in);
  ASSERT_EQ(rows.size(), 1U + 4 * 3);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"frame", "joint", "x", "y", "z"}));
  // Frame 1 (by hand): Hips (11,2,3), Elbow (10,2,3), Elbow_end (12,2,3).
  EXPECT_EQ(rows[4], (std::vector<std::string>{"1", "Hips", "11", "2", "3"}));
  EXPECT_EQ(rows[5][1], "Elbow");
  EXPECT_NEAR(std::stod(rows[5][2]), 10, 1e-12);
  EXPECT_NEAR(std::stod(rows[5][3]), 2, 1e-12);
  EXPECT_NEAR(std::stod(rows[6][2]), 12, 1e-12);
  EXPECT_EQ(rows[6][1], "Elbow_end");
  // Frame 3: Elbow at (0.5, 2 + sqrt(3)/2, 3).
  EXPECT_EQ(rows[11][0], "3");
  EXPECT_NEAR(std::stod(rows[11][3]), 2 + std::sqrt(3.0) / 2, 1e-12);
  // Without --out the CSV goes to standard output, the same bytes.
  const testing::CliResult to_stdout = testing::run_avar({"mocap", "joints", kMocapArm});
  ASSERT_EQ(to_stdout.code, kExitOk);
  std::ifstream again(csv);
  std::stringstream file_text;
  file_text << again.rdbuf();
  EXPECT_EQ(to_stdout.out, file_text.str());
}

TEST(MocapCommand, GltfJointsSampleAtTheRequestedRate) {
  const std::string glb = AVAR_SOURCE_DIR "/tests/data/mocap/gltf_short_rotation.glb";
  const testing::CliResult r = testing::run_avar({"mocap", "joints", glb, "--fps", "10"});
  ASSERT_EQ(r.code, kExitOk) << r.err;
  const auto rows = testing::csv_rows(r.out);
  ASSERT_EQ(rows.size(), 1U + 11 * 2);  // samples at 0, 0.1 ... 1 s; joints spin and tip
  // Frame 10 (t = 1 s): the tip, turned 90 deg about y, at (1, 0, 0) (worked in gltf_reader_test).
  EXPECT_EQ(rows[22][0], "10");
  EXPECT_EQ(rows[22][1], "tip");
  EXPECT_NEAR(std::stod(rows[22][2]), 1, 1e-9);
  EXPECT_NEAR(std::stod(rows[22][4]), 0, 1e-9);
  const testing::CliResult info = testing::run_avar({"mocap", "info", glb});
  ASSERT_EQ(info.code, kExitOk) << info.err;
  EXPECT_NE(info.out.find("joints: 2\n  spin  [rotation:LINEAR]\n    tip  (no channels)\n"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("frames: 31\nframe time: 0.0333333 s (30 fps)\nduration: 1 s\n"), std::string::npos) << info.out;
}

TEST(MocapCommand, BadFilesAndOptionsExitTwoWithTheirPlace) {
  const std::string broken = testing::write_temp_file("broken.bvh", "HIERARCHY\nROOT a\n{\n  OFFSET 0 0\n}\n");
  const testing::CliResult bad = testing::run_avar({"mocap", "info", broken});
  EXPECT_EQ(bad.code, kExitBadInput);
  EXPECT_EQ(bad.err, "error: " + broken + ":4:13: expected OFFSET's z (a number), found the end of the line\n");
  const testing::CliResult fps = testing::run_avar({"mocap", "joints", kMocapArm, "--fps", "60"});
  EXPECT_EQ(fps.code, kExitBadInput);
  EXPECT_NE(fps.err.find("a BVH file's rows are its frames"), std::string::npos) << fps.err;
  const testing::CliResult unknown = testing::run_avar({"mocap", "info", "take.fbx"});
  EXPECT_EQ(unknown.code, kExitBadInput);
  EXPECT_NE(unknown.err.find("take.fbx: unknown motion-capture format '.fbx'; expected .bvh, .gltf or .glb"), std::string::npos)
      << unknown.err;
  const testing::CliResult zero_fps = testing::run_avar({"mocap", "joints", "x.glb", "--fps", "0"});
  EXPECT_EQ(zero_fps.code, kExitBadInput);
  EXPECT_EQ(zero_fps.err, "error: expected --fps to be a number more than 0, found 0\n");
  EXPECT_EQ(testing::run_avar({"mocap"}).code, kExitBadInput);
  const testing::CliResult help = testing::run_avar({"mocap", "joints", "--help"});
  EXPECT_EQ(help.code, kExitOk);
  EXPECT_NE(help.out.find("frame,joint,x,y,z"), std::string::npos);
}

}  // namespace
}  // namespace avar::app
