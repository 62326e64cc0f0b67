// avar-bench-avr: the device engine's cost on an 8-bit AVR at 16 MHz, counted in CPU cycles by
// Timer1 under simavr (bench/avr/cycles_avr.cpp). Per kind of segment, the mean and worst cycles
// of one channel sample at 200 Hz, beside the target of 1,000 (16 channels at 200 Hz in a
// quarter of the CPU); the ATmega328P (an Uno) runs the build an Uno export has (steps, lines,
// cubics, Bezier), the ATmega2560 every feature. Without avr-g++ or simavr it says so and passes.
#include <cstdio>
#include <sstream>
#include <string>

#include "avar/device/tool_process.hpp"

namespace {

constexpr unsigned long kTargetCycles = 1000;

bool run(const char* mcu, const char* elf) {
  const avar::device::ToolRun r = avar::device::run_tool({"simavr", "-m", mcu, "-f", "16000000", elf}, 600);
  std::printf("%s (simavr, 16 MHz, %.1f s):\n", mcu, r.seconds);
  std::printf("  %-16s %8s %12s %12s   target mean\n", "segments", "samples", "mean cycles", "worst");
  std::stringstream in(r.output);
  bool any = false;
  for (std::string line; std::getline(in, line);) {
    const std::size_t at = line.find("cycles ");
    if (at == std::string::npos) continue;
    std::stringstream fields(line.substr(at + 7));
    std::string name;
    unsigned long samples = 0, mean = 0, worst = 0;
    if (!(fields >> name >> samples >> mean >> worst)) continue;
    std::printf("  %-16s %8lu %12lu %12lu   %lu%s\n", name.c_str(), samples, mean, worst, kTargetCycles,
                mean <= kTargetCycles ? "" : " (above)");
    any = true;
  }
  if (!any) std::printf("  no result; simavr said:\n%s\n", r.output.substr(0, 2000).c_str());
  return any;
}

}  // namespace

int main() {
#if defined(AVAR_BENCH_AVR_LEAN) && defined(AVAR_BENCH_AVR_FULL)
  if (!avar::device::find_program("simavr")) {
    std::printf("avar-bench-avr: simavr is not installed (scripts/install-deps.sh installs it); nothing measured\n");
    return 0;
  }
  const bool ok = run("atmega328p", AVAR_BENCH_AVR_LEAN) && run("atmega2560", AVAR_BENCH_AVR_FULL);
  return ok ? 0 : 1;
#else
  std::printf(
      "avar-bench-avr: avr-g++ was not found when avar was configured (scripts/install-deps.sh installs it); "
      "nothing measured\n");
  return 0;
#endif
}
