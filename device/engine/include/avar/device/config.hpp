#pragma once
// What a build of the device engine contains, and how it reads show images. The defaults: every
// segment family and channel feature, images read with a plain load (on AVR: from program memory,
// where an exported project keeps them). An exported project (avar export) carries its own copy of
// this file with only what its shows use switched on: an image that asks for a feature left out
// is refused whole (check_image: kImageNeedsFeature), and the flash of what it leaves out is saved.
// Freestanding C++14.

// Blender's easing families (sine ... elastic): about 7 KB of AVR flash.
#ifndef AVAR_DEVICE_EASINGS
#define AVAR_DEVICE_EASINGS 1
#endif
// The Cycles modifier (a channel repeated, with offset or mirrored, outside its keys).
#ifndef AVAR_DEVICE_CYCLES
#define AVAR_DEVICE_CYCLES 1
#endif
// Linear extrapolation outside a channel's keys (constant extrapolation is always there).
#ifndef AVAR_DEVICE_EXTRAPOLATION
#define AVAR_DEVICE_EXTRAPOLATION 1
#endif

// Servos on the device's own pins (a figure record's pin outputs, handed to FigureIo::pin_pulse):
// about 400 bytes of AVR flash. A figure without them refuses a record that has any.
#ifndef AVAR_DEVICE_PINS
#define AVAR_DEVICE_PINS 1
#endif

// The 32-bit fast path of steps, lines, cubics and Bezier segments (the same bits as the 64-bit
// path, two to four times faster on an 8-bit core, about 2 KB of its flash). An export leaves it
// out only when the project would not fit its target with it.
#ifndef AVAR_DEVICE_FAST
#define AVAR_DEVICE_FAST 1
#endif

// How the engine reads one byte of an image, and where the images live: on AVR program memory
// (avr/pgmspace.h; AVAR_DEVICE_IMAGES_IN_RAM keeps them in RAM instead), elsewhere a plain load
// (flash is in the address space). A build may define both macros itself.
#ifndef AVAR_DEVICE_READ_BYTE
#if defined(__AVR__) && !defined(AVAR_DEVICE_IMAGES_IN_RAM)
#include <avr/pgmspace.h>
#define AVAR_DEVICE_READ_BYTE(pointer) pgm_read_byte(pointer)
#define AVAR_DEVICE_FLASH PROGMEM
#else
#define AVAR_DEVICE_READ_BYTE(pointer) (*(pointer))
#endif
#endif
#ifndef AVAR_DEVICE_FLASH
#define AVAR_DEVICE_FLASH
#endif
