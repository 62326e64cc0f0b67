#pragma once
// The one skeleton-animation model every motion-capture importer (BVH, glTF 2.0) produces: a
// joint hierarchy with rest transforms, and every joint's local transform sampled at evenly
// spaced frames (Parent, Computer Animation, ch. 6). Units and axes are the file's own: no axis
// or unit conversion happens here (retargeting states its own).
//
// Frames: a joint's local transform maps its own frame into its parent's,
//   local = T(translation) * R(rotation) * S(scale),
// and its world transform is world(parent) * local (a root's parent is the file's origin).
// BVH: translation is the joint's OFFSET (plus position channels), rotation the channels', scale 1.
// glTF: the node's TRS (or its decomposed matrix) as animated.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

namespace avar::mocap {

inline constexpr std::ptrdiff_t kNoParent = -1;

struct Joint {
  std::string name;
  std::ptrdiff_t parent = kNoParent;  ///< index of the parent joint; parents precede children
  /// Rest (bind) local transform: BVH OFFSET with identity rotation; glTF the node's own TRS.
  Eigen::Vector3d rest_translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rest_rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d rest_scale = Eigen::Vector3d::Ones();
  bool end_site = false;  ///< a BVH End Site (named "<parent>_end"): a leaf with no channels
};

/// Local transforms of every joint at one instant (indexed like SkeletonAnimation::joints).
struct Pose {
  std::vector<Eigen::Vector3d> translation;
  std::vector<Eigen::Quaterniond> rotation;  ///< unit quaternions
  std::vector<Eigen::Vector3d> scale;
};

struct SkeletonAnimation {
  std::string source;  ///< file the animation came from (for messages)
  std::vector<Joint> joints;
  double frame_time = 1.0 / 30.0;  ///< seconds between frames, > 0
  /// frames[i]: the local pose at time i * frame_time (time 0 = the first frame). Every pose has
  /// joints.size() entries in each vector; successive rotations of a joint lie in the same
  /// hemisphere (q and -q flipped to agree), so slerp between frames turns the short way.
  std::vector<Pose> frames;
  /// What the file animates on each joint, for reports (`avar mocap info`): indexed like joints,
  /// in file order (BVH: "Xposition" ... "Zrotation"; glTF: "translation", "rotation", "scale").
  /// Empty when the importer does not describe channels; otherwise joints.size() entries.
  std::vector<std::vector<std::string>> channels;

  std::size_t frame_count() const noexcept { return frames.size(); }
  /// Time of the last frame (0 for a single frame).
  double duration() const noexcept;
  /// Index of the joint called `name`, or nullopt.
  std::optional<std::size_t> find_joint(std::string_view name) const noexcept;
};

/// The rest pose (every joint at its rest transform).
Pose rest_pose(const SkeletonAnimation& animation);

/// Checks the model's invariants (parents precede children, frame sizes, finite values, unit
/// rotations, frame_time > 0, at least one frame); throws std::invalid_argument naming the first
/// broken one. Importers call it before returning.
void validate(const SkeletonAnimation& animation);

/// The local pose at time t (seconds, clamped to [0, duration()]): translations and scales
/// interpolated linearly, rotations by slerp (playback's quaternion code), between the two
/// neighbouring frames. `out` is resized once and reused: allocation-free after the first call.
void evaluate(const SkeletonAnimation& animation, double t, Pose& out);

/// World transform of every joint for a local pose: world[j] = world[parent(j)] * local(j).
/// `world` is resized once and reused.
void forward_kinematics(const SkeletonAnimation& animation, const Pose& pose, std::vector<Eigen::Affine3d>& world);

/// Makes successive frames' rotations of each joint agree in sign (q -> -q where the dot product
/// with the previous frame's is negative). Importers and processing call it.
void align_hemispheres(SkeletonAnimation& animation) noexcept;

}  // namespace avar::mocap
