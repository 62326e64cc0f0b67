#pragma once
// What a URDF robot looks like: the <visual> elements of its links (boxes, cylinders, spheres and
// mesh files), for drawing the figure, never for its motion. Load time only; allocates.
//
// Frames: a visual's origin is in its link's frame, which is the frame of the joint the link
// hangs from (after that joint's motion), or the base frame for the root link. URDF units:
// metres, and a cylinder's axis is its frame's z.
//
// Mesh file names are resolved as ROS tools do, without ROS: `package://NAME/REST` is REST inside
// the folder NAME found by walking up from the URDF's folder (the URDF's own folder when it is
// NAME, and finally the URDF's folder itself); `file://PATH` is PATH; anything else is relative to
// the URDF's folder. Whether the file exists is the drawer's business: a figure runs without its
// meshes.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace avar::kinematics {

enum class VisualShape { box, cylinder, sphere, mesh };

struct LinkVisual {
  std::string link;   ///< the URDF link it belongs to
  std::string joint;  ///< the joint that link hangs from; empty for the root link (base frame)
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  ///< in the link's frame
  VisualShape shape = VisualShape::box;
  /// box: x, y, z sizes; cylinder: radius, length, 0; sphere: radius, 0, 0 (metres); mesh: unused.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  std::string mesh;                                 ///< mesh: the file name as the URDF writes it
  std::string mesh_path;                            ///< mesh: resolved to a path on this machine
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();  ///< mesh: per-axis scale
  std::optional<std::array<double, 4>> rgba;        ///< its material's colour (0..1), when given
};

/// The visuals of every link of a URDF document, links in document order; `folder` resolves
/// mesh file names. Throws InputError for a document urdfdom cannot read (model_from_urdf_text
/// reports the same document's problems, located, first).
std::vector<LinkVisual> visuals_from_urdf_text(const std::string& text, const std::string& file, const std::string& folder);

/// The same from a file (meshes resolved from its folder).
std::vector<LinkVisual> visuals_from_urdf_file(const std::string& path);

}  // namespace avar::kinematics
