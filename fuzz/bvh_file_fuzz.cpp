// A BVH motion capture file as a user brings it: parse_bvh must return a well-formed animation
// (finite values, one pose entry per joint, parents before children) or throw an InputError,
// nothing else.
#include <cstddef>
#include <cstdint>

#include "avar/core/input_error.hpp"
#include "avar/mocap/bvh_reader.hpp"
#include "fuzz_bytes.hpp"
#include "skeleton_animation_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    avar::fuzz::check_skeleton_animation(avar::mocap::parse_bvh(avar::fuzz::as_text(data, size), "fuzz.bvh"));
  } catch (const avar::InputError&) {
  }
  return 0;
}
