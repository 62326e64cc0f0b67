#pragma once
// The serial baud rates avar opens a port at: those a POSIX port (and libserial) sets by name.
// The rig schema validates a link's baud against this list and the serial transport maps each
// one to libserial's code (checked at compile time to cover exactly these).

#include <array>

namespace avar {

inline constexpr std::array<int, 23> kStandardBauds{300,     600,     1200,    2400,    4800,    9600,    19200,  38400,
                                                    57600,   115200,  230400,  460800,  500000,  576000,  921600, 1000000,
                                                    1152000, 1500000, 2000000, 2500000, 3000000, 3500000, 4000000};

constexpr bool is_standard_baud(long long baud) noexcept {
  for (const int b : kStandardBauds)
    if (b == baud) return true;
  return false;
}

}  // namespace avar
