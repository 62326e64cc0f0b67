# cmake -DCLOSURE=FILE -DREFUSE=devices -P check_link_closure.cmake
#
# FILE lists a program's or library's link closure, one item a line (written at configure time by
# tests/link_checks/CMakeLists.txt). Fails naming every item refused:
# - devices: anything that drives, carries or simulates a device:
#   - avar targets: the simulator (avar_sim*), the assembly of links (avar_assembly*), the control
#     loop and its I/O threads (avar_control*), input devices (avar_inputs*), the show session
#     (avar_session*), the command line (avar_app*), the whole firmware_iface module
#     (avar_firmware_iface), its drivers (avar_firmware_driver) and every transport
#     (avar_transport_*; the header-only seams of avar_transport, which the rig model names a GPIO
#     line's bias from, hold no code and pass);
#   - system libraries of transports and devices, as targets (PkgConfig::LIBSERIAL ...) or as
#     files or names: libserial, libusb-1.0, hidapi, libgpiod, rtmidi, liblo (OSC), ALSA's
#     asound, ltc, and util (openpty, for pseudo-terminals).
if(NOT CLOSURE OR NOT EXISTS "${CLOSURE}")
  message(FATAL_ERROR "no closure file '${CLOSURE}': configure the build tree first")
endif()
file(STRINGS "${CLOSURE}" items)
list(LENGTH items count)
if(count EQUAL 0)
  message(FATAL_ERROR "${CLOSURE} is empty")
endif()

set(refused "")
foreach(item IN LISTS items)
  get_filename_component(base "${item}" NAME)
  if(REFUSE STREQUAL "devices")
    if(item MATCHES "^avar_(sim|assembly|control|inputs|session|app)(_|$)"
       OR item MATCHES "^avar_(firmware_iface|firmware_driver|transport_.*)$"
       OR item MATCHES "^PkgConfig::(LIBSERIAL|LIBUSB|HIDAPI|LIBGPIOD|RTMIDI|LIBLO|ALSA|LTC)$"
       OR base MATCHES "^(lib)?(serial|usb-1\\.0|hidapi(-hidraw|-libusb)?|gpiod|rtmidi|lo|asound|ltc|util)(\\.so.*|\\.a)?$")
      list(APPEND refused "${item}")
    endif()
  else()
    message(FATAL_ERROR "REFUSE must be devices, not '${REFUSE}'")
  endif()
endforeach()

list(JOIN items ", " all)
if(refused)
  list(JOIN refused ", " names)
  message(FATAL_ERROR "${CLOSURE}: links ${names} (refused: ${REFUSE}); whole closure: ${all}")
endif()
message(STATUS "${CLOSURE}: ${count} items, none refused (${REFUSE}): ${all}")
