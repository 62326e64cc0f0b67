// A retarget map (YAML) as a user writes it, checked against examples/rigs/hello-head.yaml:
// load_retarget_map must return bindings naming channels the rig has, with finite numbers, or
// throw an InputError, nothing else. The reader takes a path, so each input is written whole to a
// file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "avar/config/retarget_map.hpp"
#include "avar/config/rig_file.hpp"
#include "avar/core/input_error.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const avar::rig::Rig rig = avar::config::load_rig_file(AVAR_FUZZ_EXAMPLES_DIR "/rigs/hello-head.yaml");
  const auto path = avar::fuzz::write_input_file("map.yaml", data, size);
  try {
    const auto map = avar::config::load_retarget_map(path.string(), rig);
    if (!std::isfinite(map.source_units)) std::abort();
    for (const auto& binding : map.rotations) {
      if (!rig.find_channel(binding.channel) || !std::isfinite(binding.scale) || !std::isfinite(binding.offset)) std::abort();
    }
    for (const auto& binding : map.positions) {
      if (!std::isfinite(binding.scale)) std::abort();
    }
  } catch (const avar::InputError&) {
  }
  return 0;
}
