# `cpack -G DEB` (or `make package`) turns an installed build into avar_<version>_<arch>.deb: the
# `avar` binary, the module libraries, their headers and the CMake package, under /usr.
# dpkg-shlibdeps reads the binary and names the Debian runtime packages it needs (libserial1,
# libyaml-cpp0.7, libusb-1.0-0, ...), so a library a new module links is listed without editing
# this file. Building against the libraries also needs the development packages recommended below.
set(CPACK_PACKAGE_NAME avar)
set(CPACK_PACKAGE_VENDOR "avar")
set(CPACK_PACKAGE_CONTACT "avar maintainers <avar@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Plays keyframed animation on animatronic figures over serial, CAN, USB and GPIO")
set(CPACK_PACKAGE_DESCRIPTION
    "avar turns keyframed curves, motion capture and inverse-kinematics targets into servo and motor commands, every tick, with every channel kept inside its limits. Shows can be tested on simulated devices that speak the hardware's bytes.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
    "libeigen3-dev, libyaml-cpp-dev, libserial-dev, libusb-1.0-0-dev, libhidapi-dev, libgpiod-dev, librtmidi-dev, liblo-dev, liburdfdom-dev, libtinyxml-dev, pkg-config")
include(CPack)
