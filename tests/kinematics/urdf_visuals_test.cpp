// What a URDF figure looks like: boxes, cylinders, spheres and mesh files per link, in their
// links' frames, with their materials' colours, and mesh names resolved without ROS.
#include "avar/kinematics/urdf_visuals.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "avar/core/input_error.hpp"

namespace avar::kinematics {
namespace {

namespace fs = std::filesystem;

const std::string kHeadFolder = AVAR_SOURCE_DIR "/examples/rigs/urdf-head";

TEST(UrdfVisuals, TheExampleHeadHasEveryShapeInDocumentOrderWithItsJointAndColour) {
  const std::vector<LinkVisual> v = visuals_from_urdf_file(kHeadFolder + "/urdf-head.urdf");
  ASSERT_EQ(v.size(), 7u);
  // The pedestal: a box on the base link (no joint: the base frame), 2 cm up.
  EXPECT_EQ(v[0].link, "base");
  EXPECT_EQ(v[0].joint, "");
  EXPECT_EQ(v[0].shape, VisualShape::box);
  EXPECT_TRUE(v[0].size.isApprox(Eigen::Vector3d(0.18, 0.18, 0.04)));
  EXPECT_TRUE(v[0].origin.translation().isApprox(Eigen::Vector3d(0, 0, 0.02)));
  ASSERT_TRUE(v[0].rgba);
  EXPECT_FLOAT_EQ(static_cast<float>((*v[0].rgba)[0]), 0.35f);
  // The neck column: a cylinder, radius then length.
  EXPECT_EQ(v[1].shape, VisualShape::cylinder);
  EXPECT_DOUBLE_EQ(v[1].size.x(), 0.018);
  EXPECT_DOUBLE_EQ(v[1].size.y(), 0.26);
  EXPECT_EQ(v[2].joint, "pan");
  // The skull: an STL found through package://urdf-head/ (the URDF's own folder).
  EXPECT_EQ(v[3].link, "skull");
  EXPECT_EQ(v[3].joint, "tilt");
  EXPECT_EQ(v[3].shape, VisualShape::mesh);
  EXPECT_EQ(v[3].mesh, "package://urdf-head/meshes/head.stl");
  EXPECT_TRUE(fs::equivalent(v[3].mesh_path, kHeadFolder + "/meshes/head.stl"));
  EXPECT_TRUE(v[3].scale.isApprox(Eigen::Vector3d::Ones()));
  // Two eyes: spheres on the fixed eye mount, either side.
  EXPECT_EQ(v[4].shape, VisualShape::sphere);
  EXPECT_DOUBLE_EQ(v[4].size.x(), 0.013);
  EXPECT_EQ(v[5].joint, "eye_mount");
  EXPECT_DOUBLE_EQ(v[5].origin.translation().y(), -0.03);
  // The jaw: an OBJ beside the URDF.
  EXPECT_EQ(v[6].joint, "jaw_hinge");
  EXPECT_TRUE(fs::equivalent(v[6].mesh_path, kHeadFolder + "/meshes/jaw.obj"));
}

TEST(UrdfVisuals, MeshNamesResolveFromPackagesAboveTheFileFromFileUrlsAndBesideIt) {
  const fs::path root = fs::temp_directory_path() / "avar_urdf_visuals";
  fs::remove_all(root);
  fs::create_directories(root / "robot_description" / "urdf");
  fs::create_directories(root / "robot_description" / "meshes");
  const fs::path urdf = root / "robot_description" / "urdf" / "arm.urdf";
  std::ofstream(urdf) << R"(<robot name="arm">
  <link name="base"><visual><geometry><mesh filename="package://robot_description/meshes/base.dae" scale="0.001 0.001 0.001"/></geometry></visual></link>
  <link name="upper"><visual><origin xyz="0 0 0.1" rpy="0 1.5707963267948966 0"/><geometry><mesh filename="file:///opt/meshes/upper.stl"/></geometry>
    <material name="red"><color rgba="1 0 0 1"/></material></visual></link>
  <link name="lower"><visual><geometry><mesh filename="lower.stl"/></geometry></visual></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="continuous"><parent link="upper"/><child link="lower"/></joint>
</robot>)";
  const std::vector<LinkVisual> v = visuals_from_urdf_file(urdf.string());
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(fs::path(v[0].mesh_path), root / "robot_description" / "meshes" / "base.dae");
  EXPECT_TRUE(v[0].scale.isApprox(Eigen::Vector3d::Constant(0.001)));
  EXPECT_FALSE(v[0].rgba);
  EXPECT_EQ(v[1].mesh_path, "/opt/meshes/upper.stl");
  EXPECT_TRUE(v[1].origin.rotation().col(2).isApprox(Eigen::Vector3d(1, 0, 0), 1e-12));  // z turned to x
  ASSERT_TRUE(v[1].rgba);
  EXPECT_EQ((*v[1].rgba)[0], 1);
  EXPECT_EQ(fs::path(v[2].mesh_path), root / "robot_description" / "urdf" / "lower.stl");
  EXPECT_EQ(v[2].joint, "elbow");
  fs::remove_all(root);
}

TEST(UrdfVisuals, AFileThatCannotBeReadIsNamed) {
  try {
    (void)visuals_from_urdf_file("no-such-robot.urdf");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-robot.urdf"), std::string::npos);
  }
}

}  // namespace
}  // namespace avar::kinematics
