// The host: standard output and exit().
#include <cstdio>
#include <cstdlib>

#include "platform.hpp"

void platform_line(const char* line) { std::printf("%s\n", line); }

void platform_exit(int status) {
  std::fflush(stdout);
  std::exit(status);
}
