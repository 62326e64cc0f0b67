// The verification run on the host: the reference the emulated targets are compared with.
#include <cstdio>

#include "golden_image.inc"
#include "verify_main.hpp"

int main() {
  avar::device::run_verification(kGoldenImage, sizeof kGoldenImage, [](const char* line) { std::printf("%s\n", line); });
  return 0;
}
