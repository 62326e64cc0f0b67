// A rig file (YAML) as a user writes it: the loader must accept it or throw an InputError, nothing
// else (no crash, no other exception, no leak, no hang).
#include <cstddef>
#include <cstdint>

#include "avar/config/rig_file.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    // A folder that does not exist: relative paths in the rig (a URDF file) name nothing.
    (void)avar::config::load_rig_text(avar::fuzz::as_text(data, size), "/nonexistent/fuzz/rig.yaml");
  } catch (const avar::InputError&) {
  }
  return 0;
}
