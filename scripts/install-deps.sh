#!/usr/bin/env bash
# Installs the Debian packages avar needs to build, test and benchmark, and only those that are
# missing. Runs unattended (CI=true, no standard input): root uses apt-get directly, anyone else
# goes through sudo. Extra packages can be named as arguments (make bench adds KDL).
set -euo pipefail

packages=(cmake ninja-build g++ pkg-config make
          libserial-dev libyaml-cpp-dev libcli11-dev libeigen3-dev
          liburdfdom-dev libtinyxml-dev
          libtinygltf-dev nlohmann-json3-dev libcivetweb-dev libsndfile1-dev libltc-dev libasound2-dev
          ola espeak-ng sox
          libusb-1.0-0-dev libhidapi-dev libgpiod-dev librtmidi-dev liblo-dev
          libgtest-dev libgmock-dev libbenchmark-dev
          python3-can
          emscripten node-acorn chromium
          gcc-avr avr-libc simavr gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
          mkdocs mkdocs-material
          clang-format clang-tidy "$@")

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "avar: all build dependencies are installed"
  exit 0
fi

echo "avar: installing missing packages: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo -n)
  if ! sudo -n true 2>/dev/null; then
    if [ -t 0 ]; then as_root=(sudo); else
      echo "avar: need root to install packages and sudo asks for a password; run:" >&2
      echo "  sudo apt-get install -y ${missing[*]}" >&2
      exit 1
    fi
  fi
else
  echo "avar: not root and no sudo; as root, run: apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" </dev/null
