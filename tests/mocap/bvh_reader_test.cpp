#include "avar/mocap/bvh_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "avar/core/input_error.hpp"
#include "../support/input_errors.hpp"
#include "joint_positions.hpp"

namespace avar::mocap {
namespace {

using testing::mocap_fixture;

std::string bvh_fixture_text(const std::string& name) {
  std::ifstream in(mocap_fixture(name), std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

#define EXPECT_BVH_AT(animation, frame, joint, x, y, z) EXPECT_JOINT_AT(animation, frame, joint, x, y, z, 1e-9)

// Expected positions below are worked by hand from the BVH convention (rotations in degrees, the
// first listed channel outermost; translation = OFFSET + position channels) with the right-handed
// quarter turns Rx: (x,y,z) -> (x,-z,y), Ry: (x,y,z) -> (z,y,-x), Rz: (x,y,z) -> (-y,x,z).

TEST(BvhReaderFixtures, ZxyArmWithRootPositionAndEndSite) {
  const SkeletonAnimation a = load_bvh(mocap_fixture("zxy_arm.bvh"));
  ASSERT_EQ(a.joints.size(), 3U);
  EXPECT_EQ(a.joints[2].name, "Elbow_end");
  EXPECT_TRUE(a.joints[2].end_site);
  EXPECT_EQ(a.joints[1].parent, 0);
  EXPECT_EQ(a.frame_count(), 4U);
  EXPECT_DOUBLE_EQ(a.frame_time, 0.04);
  ASSERT_EQ(a.channels.size(), 3U);
  EXPECT_EQ(a.channels[0],
            (std::vector<std::string>{"Xposition", "Yposition", "Zposition", "Zrotation", "Xrotation", "Yrotation"}));
  EXPECT_TRUE(a.channels[2].empty());
  // Frame 0, rest: Hips at its OFFSET, children at the OFFSET sums.
  EXPECT_BVH_AT(a, 0, "Hips", 1, 2, 3);
  EXPECT_BVH_AT(a, 0, "Elbow", 1, 3, 3);
  EXPECT_BVH_AT(a, 0, "Elbow_end", 1, 3, 5);
  // Frame 1: Hips at OFFSET + (10,0,0) = (11,2,3), turned Rz90; Elbow = Hips + Rz(0,1,0) = +(-1,0,0);
  // end = Elbow + Rz Rx (0,0,2) = Rz (0,-2,0) = +(2,0,0).
  EXPECT_BVH_AT(a, 1, "Hips", 11, 2, 3);
  EXPECT_BVH_AT(a, 1, "Elbow", 10, 2, 3);
  EXPECT_BVH_AT(a, 1, "Elbow_end", 12, 2, 3);
  // Frame 2: Hips Z=90 X=90 is Rz Rx: Elbow = Hips + Rz Rx (0,1,0) = Rz (0,0,1) = +(0,0,1)
  // (Rx Rz would give (-1,0,0)); end = Elbow + Rz Rx (0,0,2) = +(2,0,0).
  EXPECT_BVH_AT(a, 2, "Elbow", 1, 2, 4);
  EXPECT_BVH_AT(a, 2, "Elbow_end", 3, 2, 4);
  // Frame 3: Hips Z=30: Elbow = Hips + (-sin 30, cos 30, 0).
  EXPECT_BVH_AT(a, 3, "Elbow", 0.5, 2 + std::sqrt(3.0) / 2, 3);
  EXPECT_BVH_AT(a, 3, "Elbow_end", 0.5, 2 + std::sqrt(3.0) / 2, 5);
}

TEST(BvhReaderFixtures, XyzYzxAndSixChannelsInMixedOrder) {
  const SkeletonAnimation a = load_bvh(mocap_fixture("orders.bvh"));
  ASSERT_EQ(a.joints.size(), 4U);
  // Frame 0: Base X=90 Y=90 is Rx Ry. Link = Rx Ry (1,0,0) = Rx (0,0,-1) = (0,1,0);
  // Tip = Link + Rx Ry (0,0,1) = Rx (1,0,0) = +(1,0,0); end = Tip + Rx Ry (0,1,0) = +(0,0,1).
  EXPECT_BVH_AT(a, 0, "Base", 0, 0, 0);
  EXPECT_BVH_AT(a, 0, "Link", 0, 1, 0);
  EXPECT_BVH_AT(a, 0, "Tip", 1, 1, 0);
  EXPECT_BVH_AT(a, 0, "Tip_end", 1, 1, 1);
  // Frame 1: Link Y=90 Z=90 is Ry Rz; Tip translation = (0,0,1) + (3,2,0) = (3,2,1);
  // Tip = (1,0,0) + Ry Rz (3,2,1) = Ry (-2,3,1) = +(1,3,2); end = Tip + Ry Rz (0,1,0) = Ry (-1,0,0) = +(0,0,1).
  EXPECT_BVH_AT(a, 1, "Link", 1, 0, 0);
  EXPECT_BVH_AT(a, 1, "Tip", 2, 3, 2);
  EXPECT_BVH_AT(a, 1, "Tip_end", 2, 3, 3);
  // Frame 2: Tip Z=90 X=90 (its channels list Z, then X, then Y) is Rz Rx: end = Tip + Rz Rx (0,1,0) = Rz (0,0,1).
  EXPECT_BVH_AT(a, 2, "Tip", 1, 0, 1);
  EXPECT_BVH_AT(a, 2, "Tip_end", 1, 0, 2);
}

TEST(BvhReaderFixtures, CrlfTabsTrailingSpacesAndBlankLinesReadTheSame) {
  std::string text = bvh_fixture_text("zxy_arm.bvh");
  std::string messy;
  for (const char c : text) {
    if (c == '\n') messy += "  \t\r\n\r\n";
    else if (c == ' ') messy += "\t ";
    else messy += c;
  }
  const SkeletonAnimation clean = parse_bvh(text, "clean.bvh");
  const SkeletonAnimation read = parse_bvh(messy, "messy.bvh");
  ASSERT_EQ(read.frame_count(), clean.frame_count());
  ASSERT_EQ(read.joints.size(), clean.joints.size());
  for (std::size_t f = 0; f < clean.frame_count(); ++f)
    for (std::size_t j = 0; j < clean.joints.size(); ++j) {
      EXPECT_EQ(read.frames[f].translation[j], clean.frames[f].translation[j]);
      EXPECT_TRUE(read.frames[f].rotation[j].isApprox(clean.frames[f].rotation[j], 0));
    }
  EXPECT_EQ(read.joints[0].name, "Hips");
}

TEST(BvhReaderFixtures, NamesWithSpacesBracesOnTheLineAndSuccessiveRotationsInOneHemisphere) {
  // 170 then -170 degrees about Z: as quaternions these lie in opposite hemispheres unless aligned.
  const std::string text =
      "HIERARCHY\nROOT Bip01 Pelvis {\nOFFSET 0 0 0\nCHANNELS 1 Zrotation\n"
      "End Site {\nOFFSET 1 0 0\n}\n}\nMOTION\nFrames: 2\nFrame Time: 0.5\n170\n-170\n";
  const SkeletonAnimation a = parse_bvh(text, "named.bvh");
  EXPECT_EQ(a.joints[0].name, "Bip01 Pelvis");
  EXPECT_EQ(a.joints[1].name, "Bip01 Pelvis_end");
  EXPECT_GT(a.frames[0].rotation[0].dot(a.frames[1].rotation[0]), 0);
  // Halfway the slerp passes 180 degrees (the short way), not 0.
  Pose pose;
  evaluate(a, 0.25, pose);
  std::vector<Eigen::Affine3d> world;
  forward_kinematics(a, pose, world);
  EXPECT_LT((world[1].translation() - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-9);
}

/// The error of parsing `text` after its "file:" prefix: "LINE:COLUMN: problem".
std::string bvh_error(const std::string& text) {
  return ::avar::testing::load_error([](const std::string& path) { load_bvh(path); }, text, "broken.bvh");
}

const std::string kBvhGood =
    "HIERARCHY\n"                                   // 1
    "ROOT Hips\n"                                   // 2
    "{\n"                                           // 3
    "  OFFSET 0 0 0\n"                              // 4
    "  CHANNELS 3 Zrotation Xrotation Yrotation\n"  // 5
    "  JOINT Neck\n"                                // 6
    "  {\n"                                         // 7
    "    OFFSET 0 1 0\n"                            // 8
    "    CHANNELS 1 Xrotation\n"                    // 9
    "    End Site\n"                                // 10
    "    {\n"                                       // 11
    "      OFFSET 0 1 0\n"                          // 12
    "    }\n"                                       // 13
    "  }\n"                                         // 14
    "}\n"                                           // 15
    "MOTION\n"                                      // 16
    "Frames: 2\n"                                   // 17
    "Frame Time: 0.1\n"                             // 18
    "1 2 3 4\n"                                     // 19
    "5 6 7 8\n";                                    // 20

TEST(BvhReaderErrors, EachMalformedClassIsRefusedWithItsLocation) {
  using ::avar::testing::replace;
  EXPECT_EQ(bvh_error(kBvhGood), "");
  // Truncated hierarchy.
  EXPECT_EQ(bvh_error(kBvhGood.substr(0, kBvhGood.find("  }\n}"))),
            ":14:1: expected '}' closing joint 'Neck' (opened at line 7), found the end of the file");
  // Row value counts.
  EXPECT_EQ(bvh_error(replace(kBvhGood, "5 6 7 8", "5 6 7")), ":20:6: frame 1 holds 3 values; expected one per channel (4)");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "5 6 7 8", "5 6 7 8 9")),
            ":20:9: frame 1 holds more than 4 values; expected one per channel (4)");
  // Rows against Frames:.
  EXPECT_EQ(bvh_error(replace(kBvhGood, "Frames: 2", "Frames: 3")),
            ":21:1: the file ends after 2 rows; expected 3 frames as 'Frames:' declares");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "Frames: 2", "Frames: 1")), ":20:1: more rows than the 1 frames 'Frames:' declares");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "Frames: 2", "Frames: 0")),
            ":17:9: expected a frame count of at least 1 after 'Frames:', found '0'");
  // Numbers.
  EXPECT_EQ(bvh_error(replace(kBvhGood, "5 6 7 8", "5 6x 7 8")), ":20:3: expected a channel value (a number), found '6x'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "5 6 7 8", "5 6 nan 8")),
            ":20:5: expected a channel value to be a finite number, found 'nan'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "5 6 7 8", "5 6 7 -inf")),
            ":20:7: expected a channel value to be a finite number, found '-inf'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "5 6 7 8", "5 6 7 1e999")),
            ":20:7: expected a channel value to be a finite number, found '1e999'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "OFFSET 0 1 0\n    CH", "OFFSET 0 1\n    CH")),
            ":8:15: expected OFFSET's z (a number), found the end of the line");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "Frame Time: 0.1", "Frame Time: 0")),
            ":18:13: expected a frame time of more than 0 s, found '0'");
  // Braces.
  EXPECT_EQ(bvh_error(replace(kBvhGood, "  JOINT Neck\n  {\n", "  JOINT Neck\n")),
            ":7:5: expected '{' opening 'Neck', found 'OFFSET'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "      OFFSET 0 1 0\n", "      OFFSET 0 1 0\n      OFFSET 1 1 1\n")),
            ":13:7: expected '}' closing the End Site opened at line 11, found 'OFFSET'");
  // Unknown keywords and channels.
  EXPECT_EQ(bvh_error(replace(kBvhGood, "  JOINT Neck", "  BONE Neck")),
            ":6:3: expected OFFSET, CHANNELS, JOINT, End Site or '}' in joint 'Hips', found 'BONE'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "Xrotation\n    End", "Wrotation\n    End")),
            ":9:16: expected channel 1 of 1 (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation), "
            "found 'Wrotation'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 3 Zrotation Zrotation Yrotation")),
            ":5:24: channel Zrotation is listed twice; expected each at most once");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "HIERARCHY", "HIERARCHIE")),
            ":1:1: expected 'HIERARCHY' at the start of a BVH file, found 'HIERARCHIE'");
  EXPECT_EQ(bvh_error(replace(kBvhGood, "MOTION", "MOTIONS")), ":16:1: expected 'MOTION' after the hierarchy, found 'MOTIONS'");
  // Several roots.
  EXPECT_EQ(bvh_error(replace(kBvhGood, "}\nMOTION", "}\nROOT Other\n{\nOFFSET 0 0 0\n}\nMOTION")),
            ":16:1: a second ROOT; expected one skeleton per file, then MOTION");
  // Duplicate names.
  EXPECT_EQ(bvh_error(replace(kBvhGood, "JOINT Neck", "JOINT Hips")),
            ":6:9: joint name 'Hips' is used twice (first at line 2); expected unique names");
  EXPECT_EQ(bvh_error(""), ":1:1: expected 'HIERARCHY' at the start of a BVH file, found the end of the file");
}

TEST(BvhReaderErrors, MissingFileNamesIt) {
  try {
    load_bvh("/nonexistent/dir/x.bvh");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/dir/x.bvh: cannot read the file", 0), 0U) << e.what();
  }
}

TEST(BvhReaderErrors, SeededMutationsEitherParseOrThrowInputError) {
  // A small fuzz family: random byte edits of a good file never crash nor throw anything else.
  const unsigned seed = 20261203;
  std::mt19937 random(seed);
  const auto pick = [&random](std::size_t n) { return static_cast<std::size_t>(random() % n); };
  const std::string bytes = " \n\r\t{}-+.e0123456789XYZrotationpsiHIERARCHYROOTJOINTEndSiteMOTIONFrames:";
  for (int trial = 0; trial < 2000; ++trial) {
    std::string text = kBvhGood;
    const std::size_t edits = 1 + pick(4);
    for (std::size_t e = 0; e < edits; ++e) {
      const std::size_t at = pick(text.size());
      const char c = bytes[pick(bytes.size())];
      switch (pick(3)) {
        case 0: text[at] = c; break;
        case 1: text.insert(at, 1, c); break;
        default: text.erase(at, 1); break;
      }
    }
    try {
      parse_bvh(text, "mutated.bvh");
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << "seed " << seed << " trial " << trial << ": " << e.what() << "\n" << text;
    }
  }
}

}  // namespace
}  // namespace avar::mocap
