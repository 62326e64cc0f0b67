#!/bin/sh
# Installs a built avar tree into a temporary prefix, then configures, builds and runs
# tests/package_consumer against it with find_package(avar CONFIG REQUIRED): the exported targets,
# the installed headers and avarConfig.cmake's dependencies must be enough for another project.
# Usage: package_consumer_test.sh BUILD_DIR SOURCE_DIR CXX_COMPILER [CXX_FLAGS]
set -eu
build=$1
source=$2
compiler=$3
flags=${4:-}

work=$(mktemp -d "${TMPDIR:-/tmp}/avar-package-XXXXXX")
trap 'rm -rf "$work"' EXIT

# Everything the install copies (ctest may run before a partial build has built all of it).
cmake --build "$build" --target avar_installable
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
test -x "$work/prefix/bin/avar"

launcher=
if command -v ccache >/dev/null 2>&1; then launcher=-DCMAKE_CXX_COMPILER_LAUNCHER=ccache; fi
cmake -S "$source/tests/package_consumer" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="$flags" $launcher >"$work/configure.log" || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer" || exit 1

out=$("$work/consumer/package_consumer" "$source/examples/rigs/hello-head.yaml" "$source/examples/shows/hello-head.yaml")
echo "$out"
echo "$out" | grep -qx 'curve(0.5) = 2.5'
echo "$out" | grep -qx 'rig channels = 8'
# The installed binary runs and reads the same files.
"$work/prefix/bin/avar" check "$source/examples/shows/hello-head.yaml" --rig "$source/examples/rigs/hello-head.yaml" >/dev/null
echo "package consumer: ok"
