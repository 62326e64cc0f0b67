# Warnings are errors for every avar target; sanitizers are opt-in per build tree.
add_library(avar_build_flags INTERFACE)
target_compile_options(avar_build_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  -Wnon-virtual-dtor -Woverloaded-virtual -Werror)

if(AVAR_SANITIZE)
  target_compile_options(avar_build_flags INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(avar_build_flags INTERFACE -fsanitize=address,undefined)
endif()
if(AVAR_TSAN)
  target_compile_options(avar_build_flags INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(avar_build_flags INTERFACE -fsanitize=thread)
endif()
