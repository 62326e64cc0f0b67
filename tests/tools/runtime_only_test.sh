#!/bin/sh
# Fails when the program PROGRAM needs a shared library other than the C and C++ runtimes (libc,
# libm, libstdc++, libgcc_s, the dynamic loader) or a sanitizer's runtime: proof that what it links
# brings no system library (serial, USB, GPIO, MIDI, OSC, ...) with it.
# Usage: runtime_only_test.sh PROGRAM
set -eu
program=$1
if ! dynamic=$(readelf -d "$program"); then
  echo "cannot read the dynamic section of $program (not built?)"
  exit 1
fi
needed=$(printf '%s\n' "$dynamic" | sed -n 's/.*(NEEDED).*\[\(.*\)\].*/\1/p' | tr '\n' ' ')
case " $needed " in
  *" libc.so."*) ;;
  *)
    echo "$program names no libc among its shared libraries: not a dynamically linked program?"
    exit 1
    ;;
esac
echo "$program needs:" $needed
status=0
for library in $needed; do
  case $library in
    libc.so.* | libm.so.* | libstdc++.so.* | libgcc_s.so.* | ld-linux*.so.* | libasan.so.* | libubsan.so.* | libtsan.so.*) ;;
    *)
      echo "not a runtime library: $library"
      status=1
      ;;
  esac
done
exit $status
