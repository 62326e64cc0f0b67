// The codecs a board shares with the host (PCA9685, the Maestro's framing) compile as the Arduino
// IDE compiles a library's sources for an Uno: avr-g++ 5.4 at gnu++11, freestanding, every warning
// an error. The device verification builds them at C++14 for the emulated targets; this holds them
// to the older dialect and the warnings an exported library is built with.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace avar::device {
namespace shared_codecs_test {

TEST(SharedCodecs, CompileAsAnArduinoLibraryForAnUno) {
  if (std::system("command -v avr-g++ > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "avr-g++ is not installed (scripts/install-deps.sh installs it)";
  const std::string codec = AVAR_SOURCE_DIR "/firmware_iface/codec";
  for (const char* source : {"pca9685_codec.cpp", "maestro_codec.cpp"}) {
    const std::string compile =
        "avr-g++ -mmcu=atmega328p -std=gnu++11 -ffreestanding -fsyntax-only -Wall -Wextra -Wpedantic "
        "-Wshadow -Wconversion -Werror -I" +
        codec + "/include " + codec + "/src/" + source;
    EXPECT_EQ(std::system(compile.c_str()), 0) << compile;
  }
}

}  // namespace shared_codecs_test
}  // namespace avar::device
