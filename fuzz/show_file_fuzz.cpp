// A show file (YAML) as a user or an exporter writes it: the loader must build every curve or
// throw an InputError, nothing else.
#include <cstddef>
#include <cstdint>

#include "avar/config/show_file.hpp"
#include "fuzz_bytes.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)avar::config::load_show_text(avar::fuzz::as_text(data, size), "fuzz-show.yaml");
  } catch (const avar::InputError&) {
  }
  return 0;
}
