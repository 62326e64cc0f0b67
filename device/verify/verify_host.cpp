// The verification run on the host: the reference the emulated targets are compared with.
#include "golden_image.inc"
#include "platform.hpp"
#include "verify_main.hpp"

int main() {
  avar::device::run_verification(kGoldenImage, sizeof kGoldenImage, platform_line);
  return 0;
}
