#pragma once
// Joint trees from URDF robot descriptions (read by urdfdom, Debian's liburdfdom-dev), so that
// users can bring a description they already have. Load time only: allocates and throws
// InputError naming the file, line and column of the offending element, what was found and what
// was expected.
//
// Mapping: every URDF joint becomes a Model joint of the same name, parents before children
// (depth first from the root link). revolute -> revolute with its <limit>; continuous ->
// revolute limited to +-2 pi (one full turn either way: the Model needs finite limits);
// prismatic -> prismatic with its <limit>; fixed -> fixed. origin xyz (m) / rpy (rad, fixed axes
// roll about x, pitch about y, yaw about z) gives the joint origin; <axis xyz> the axis (default
// 1 0 0). Every link but the root becomes an effector of the same name at its joint's frame
// (a URDF link frame is the frame of the joint it hangs from).

#include <string>

#include "avar/kinematics/model.hpp"

namespace avar::kinematics {

/// Reads a URDF file. Rejects: a file that cannot be read or is not well-formed XML, no <robot>,
/// a joint with no name, no or an unknown type (floating and planar are not supported), a
/// revolute or prismatic joint without <limit lower upper> or with lower > upper, a zero axis,
/// a missing <parent link> or <child link>, a link that is not declared, a link with two parent
/// joints, a cycle of joints, more than one root link, and anything urdfdom itself refuses.
Model model_from_urdf_file(const std::string& path);

/// The same from the text of a document; `file` names it in errors.
Model model_from_urdf_text(const std::string& text, const std::string& file);

}  // namespace avar::kinematics
