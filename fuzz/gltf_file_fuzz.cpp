// A glTF 2.0 file (JSON .gltf or binary .glb) as a user brings it: load_gltf must return a
// well-formed animation (finite values, unit rotations, one pose entry per joint, parents before
// children) or throw an InputError, nothing else. The reader takes a path, so each input is
// written whole to a file; the first byte's low bit picks the name's extension (.glb or .gltf:
// the reader goes by the "glTF" magic, the name must not matter). Buffer URIs naming other files
// find nothing there (data: URIs are read).
#include <cstddef>
#include <cstdint>

#include "avar/core/input_error.hpp"
#include "avar/mocap/gltf_reader.hpp"
#include "input_file.hpp"
#include "skeleton_animation_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary_name = size > 0 && (data[0] & 1U) != 0;
  const auto path = avar::fuzz::write_input_file(binary_name ? "input.glb" : "input.gltf", data, size);
  try {
    avar::fuzz::check_skeleton_animation(avar::mocap::load_gltf(path.string()));
  } catch (const avar::InputError&) {
  }
  return 0;
}
