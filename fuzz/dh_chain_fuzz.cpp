// A DH chain text file (the IK benchmark's chain format): the reader must return chains or throw
// an InputError, and every chain it returns must build into a model or be refused the same way.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include "avar/core/input_error.hpp"
#include "avar/kinematics/chain_text_reader.hpp"
#include "avar/kinematics/denavit_hartenberg.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream text(avar::fuzz::as_text(data, size));
  try {
    for (const avar::kinematics::DhChain& chain : avar::kinematics::read_dh_chains(text, "fuzz-chains.txt")) {
      try {
        (void)avar::kinematics::chain_from_standard_dh(chain.rows);
      } catch (const avar::InputError&) {
      }
    }
  } catch (const avar::InputError&) {
  }
  return 0;
}
