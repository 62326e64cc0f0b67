#pragma once
// What a run under an emulator needs of its platform: a line out, and the end of the run. One
// implementation per platform (platform_host.cpp, platform_avr.cpp: UART0 under simavr,
// platform_arm.cpp: semihosting under QEMU, with the vectors and start-up a bare Cortex-M needs).
// Shared by the engine's bit-identity run and avar export's verification of an exported project.

/// Prints one line (without its newline) on the platform's console.
void platform_line(const char* line);
/// Ends the run with `status` (the emulator exits; on the host, the process).
[[noreturn]] void platform_exit(int status);
