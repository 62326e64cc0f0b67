# Third-party libraries, all from Debian packages (scripts/install-deps.sh installs them).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
pkg_check_modules(LIBSERIAL REQUIRED IMPORTED_TARGET libserial)
# Native USB (Maestro), HID gamepads, GPIO (v1.6 API), MIDI (ALSA sequencer) and OSC.
pkg_check_modules(LIBUSB REQUIRED IMPORTED_TARGET libusb-1.0)
pkg_check_modules(HIDAPI REQUIRED IMPORTED_TARGET hidapi-hidraw)
pkg_check_modules(LIBGPIOD REQUIRED IMPORTED_TARGET libgpiod)
pkg_check_modules(RTMIDI REQUIRED IMPORTED_TARGET rtmidi)
pkg_check_modules(LIBLO REQUIRED IMPORTED_TARGET liblo)
# Sound files (WAV, FLAC, OGG) for the jaw-from-audio track source.
pkg_check_modules(SNDFILE REQUIRED IMPORTED_TARGET sndfile)
# Rhubarb Lip Sync's JSON mouth cues.
find_package(nlohmann_json REQUIRED)
# HTTP and WebSocket for the studio's server: CivetWeb, one small embeddable C library for both.
# Found by hand: Debian's CMake package for it names a server binary the -dev package lacks.
find_path(CIVETWEB_INCLUDE_DIR civetweb.h REQUIRED)
find_library(CIVETWEB_LIBRARY civetweb REQUIRED)
# SMPTE linear timecode (LTC) decoding for the timecode chase.
pkg_check_modules(LTC REQUIRED IMPORTED_TARGET ltc)
# ALSA PCM capture: LTC from a sound card input (--timecode ltc:alsa:DEVICE).
pkg_check_modules(ALSA REQUIRED IMPORTED_TARGET alsa)
if(AVAR_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(AVAR_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
# glTF 2.0 motion capture (mocap): Debian's shared tinygltf, its JSON from nlohmann-json.
find_package(TinyGLTF REQUIRED)
find_package(nlohmann_json REQUIRED)
