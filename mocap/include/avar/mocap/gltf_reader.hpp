#pragma once
// glTF 2.0 (.gltf with .bin or data URIs, and .glb) skeletal animation into the skeleton-animation
// model, through tinygltf. Load time only: allocates and throws; not for the tick.
//
// Skeleton: the joints of the first skin and all their ancestors; without a skin, the nodes the
// animation targets and all their ancestors. Joints come in depth-first order from the roots
// (parents before children), named by the node's name ("node<i>" when it has none; a repeated
// name gets "_node<i>" appended). Rest transforms are the nodes' TRS; a node given by a matrix has
// it decomposed into translation, rotation and scale (a matrix with shear is refused).
//
// Animation: one animation (options.animation, default the first); its translation, rotation and
// scale channels on skeleton nodes (weights and channels on other nodes are ignored), with LINEAR
// (slerp for rotations), STEP and CUBICSPLINE samplers as the specification defines them, and
// accessors of any component type (normalized integers by the spec's formulas; sparse accessors
// applied). The model's frames are samples at t_i = i / sample_rate_hz seconds, i = 0 .. while
// t_i <= the latest key time; before a channel's first key its first value holds, after its last
// the last. A file without animations gives one frame, the rest pose. Units and axes are the
// file's (glTF: metres, +Y up), untouched. SkeletonAnimation::channels lists each joint's
// animated paths with their interpolation, e.g. "rotation:CUBICSPLINE".
//
// Every problem throws avar::InputError naming the file and the JSON path, e.g.
// "walk.gltf: animations[0].samplers[2].output: accessor 7 out of range (the file has 5)".

#include <cstddef>
#include <string>

#include "avar/mocap/skeleton_animation.hpp"

namespace avar::mocap {

struct GltfReadOptions {
  double sample_rate_hz = 30;  ///< samples per second, > 0
  std::size_t animation = 0;   ///< which of the file's animations
};

/// Reads, samples and validates the glTF file at `path` (binary when it starts with the .glb
/// magic "glTF", otherwise JSON).
SkeletonAnimation load_gltf(const std::string& path, const GltfReadOptions& options = {});

}  // namespace avar::mocap
