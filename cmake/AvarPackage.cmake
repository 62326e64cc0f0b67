# Installing avar: the module libraries (static), their public headers, the `avar` binary and an
# exported CMake package, so that another project writes
#   find_package(avar CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE avar::playback avar::kinematics)
# Every library declared with avar_module() is installed and exported as avar::<module> without
# further work; avar_install_library() does the same for a library declared by hand.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(AVAR_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/avar)

# avar_install_library(TARGET EXPORT_NAME INCLUDE_DIRS...): installs TARGET into the avarTargets
# export set as avar::EXPORT_NAME with the contents of each INCLUDE_DIR (a folder holding avar/...)
# under <prefix>/include.
function(avar_install_library target export_name)
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  install(TARGETS ${target} EXPORT avarTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT Development
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT Development
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  # A folder of headers that several libraries share (the layers of firmware_iface) is installed once.
  get_property(installed_dirs GLOBAL PROPERTY AVAR_INSTALLED_INCLUDE_DIRS)
  foreach(dir IN LISTS ARGN)
    if(NOT dir IN_LIST installed_dirs)
      install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT Development)
      set_property(GLOBAL APPEND PROPERTY AVAR_INSTALLED_INCLUDE_DIRS ${dir})
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY AVAR_INSTALLED_LIBRARIES ${target})
endfunction()

# The find_dependency() / pkg_check_modules() lines avarConfig.cmake needs for ITEM, one entry of an
# installed library's link interface, appended to the list named by OUT.
function(_avar_dependency_of item out)
  set(lines ${${out}})
  string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
  if(item MATCHES "^\\$<" OR item MATCHES "^avar_" OR item MATCHES "^avar::" OR item MATCHES "^-")
    # Generator expressions left are build-tree only; the project's own targets are exported.
  elseif(item MATCHES "^PkgConfig::(.+)$")
    set(prefix ${CMAKE_MATCH_1})
    if(NOT DEFINED CACHE{${prefix}_MODULE_NAME})
      message(FATAL_ERROR "avar package: ${item} is linked by an installed library, but "
                          "${prefix}_MODULE_NAME is unknown (give pkg_check_modules one module per prefix)")
    endif()
    list(APPEND lines "pkg_check_modules(${prefix} REQUIRED QUIET IMPORTED_TARGET $CACHE{${prefix}_MODULE_NAME})")
  elseif(item STREQUAL "Threads::Threads")
    list(APPEND lines "find_dependency(Threads)")
  elseif(TARGET ${item})
    # An imported target from a CMake package: the package is named as the namespace (Eigen3::Eigen,
    # TinyGLTF::TinyGLTF) or, without one, as the target (yaml-cpp).
    string(REGEX REPLACE "::.*$" "" package "${item}")
    if(NOT DEFINED ${package}_DIR)
      message(FATAL_ERROR "avar package: cannot tell which package provides ${item}, linked by an "
                          "installed library; teach cmake/AvarPackage.cmake")
    endif()
    list(APPEND lines "find_dependency(${package} CONFIG)")
  endif()
  # Anything else is a plain system library (util, m) that the linker finds by itself.
  set(${out} ${lines} PARENT_SCOPE)
endfunction()

# Called once, after every module is declared: writes the package files and the CPack settings.
function(avar_install_package)
  get_property(libraries GLOBAL PROPERTY AVAR_INSTALLED_LIBRARIES)
  set(dependency_lines)
  foreach(target IN LISTS libraries)
    get_target_property(interface ${target} INTERFACE_LINK_LIBRARIES)
    if(interface)
      foreach(item IN LISTS interface)
        _avar_dependency_of("${item}" dependency_lines)
      endforeach()
    endif()
  endforeach()
  list(REMOVE_DUPLICATES dependency_lines)
  if(dependency_lines MATCHES "pkg_check_modules")
    list(PREPEND dependency_lines "find_dependency(PkgConfig)")
  endif()
  list(JOIN dependency_lines "\n" AVAR_PACKAGE_DEPENDENCIES)

  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/avarConfig.cmake.in
                                ${PROJECT_BINARY_DIR}/avarConfig.cmake INSTALL_DESTINATION ${AVAR_INSTALL_CMAKEDIR})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/avarConfigVersion.cmake
                                   COMPATIBILITY SameMinorVersion)
  # What `cmake --install` copies, as one target to build first.
  add_custom_target(avar_installable)
  add_dependencies(avar_installable avar ${libraries})

  install(EXPORT avarTargets NAMESPACE avar:: DESTINATION ${AVAR_INSTALL_CMAKEDIR} COMPONENT Development)
  install(FILES ${PROJECT_BINARY_DIR}/avarConfig.cmake ${PROJECT_BINARY_DIR}/avarConfigVersion.cmake
          DESTINATION ${AVAR_INSTALL_CMAKEDIR} COMPONENT Development)
endfunction()
