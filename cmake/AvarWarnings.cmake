# The same warnings for every avar target, errors with AVAR_WERROR (the project's own builds);
# sanitizers are opt-in per build tree.
add_library(avar_build_flags INTERFACE)
target_compile_options(avar_build_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Woverloaded-virtual)
if(AVAR_WERROR)
  target_compile_options(avar_build_flags INTERFACE -Werror)
endif()

if(AVAR_SANITIZE)
  target_compile_options(avar_build_flags INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(avar_build_flags INTERFACE -fsanitize=address,undefined)
endif()
if(AVAR_TSAN)
  target_compile_options(avar_build_flags INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(avar_build_flags INTERFACE -fsanitize=thread)
endif()
# The libFuzzer tree (`make fuzz`, clang only): every library carries libFuzzer's coverage
# instrumentation and ASan+UBSan; the fuzz targets themselves link libFuzzer (fuzz/CMakeLists.txt).
if(AVAR_LIBFUZZER)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "AVAR_LIBFUZZER needs clang (CMAKE_CXX_COMPILER=clang++-14)")
  endif()
  target_compile_options(avar_build_flags INTERFACE
    -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(avar_build_flags INTERFACE -fsanitize=address,undefined)
endif()
# The sanitizer trees (what `make test` and CI build) compile the libraries eight files to a unit
# as well, which roughly halves their build: file-local names must differ within a module. The
# optimised tree keeps one unit per file, so that benchmarks measure the code as shipped.
if(AVAR_SANITIZE OR AVAR_TSAN OR AVAR_LIBFUZZER)
  set(CMAKE_UNITY_BUILD ON)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE 8)
endif()
