// A URDF robot description a user brings: the importer must build a joint tree or throw an
// InputError (TinyXML and urdfdom included), nothing else.
#include <cstddef>
#include <cstdint>

#include "avar/core/input_error.hpp"
#include "avar/kinematics/urdf_import.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)avar::kinematics::model_from_urdf_text(avar::fuzz::as_text(data, size), "fuzz.urdf");
  } catch (const avar::InputError&) {
  }
  return 0;
}
