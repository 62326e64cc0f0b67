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
# The sanitizer trees (what `make test` and CI build) compile the libraries eight files to a unit
# as well, which roughly halves their build: file-local names must differ within a module. The
# optimised tree keeps one unit per file, so that benchmarks measure the code as shipped.
if(AVAR_SANITIZE OR AVAR_TSAN)
  set(CMAKE_UNITY_BUILD ON)
  set(CMAKE_UNITY_BUILD_BATCH_SIZE 8)
endif()
