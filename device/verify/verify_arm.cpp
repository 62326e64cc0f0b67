// The verification run on a Cortex-M board under QEMU (platform_arm.cpp).
#include "golden_image.inc"
#include "platform.hpp"
#include "verify_main.hpp"

int main() {
  avar::device::run_verification(kGoldenImage, sizeof kGoldenImage, platform_line);
  return 0;
}
