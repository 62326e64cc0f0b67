# avar_module(NAME [FOLDER SUB] SOURCES ... DEPS ...) declares the library of one top-level folder:
# target avar_NAME, alias avar::NAME, public headers under NAME/include/avar/NAME/.
# With FOLDER, one layer of a module kept in a sub-folder (firmware_iface/codec): its public headers
# are under SUB/include/; several libraries may share one sub-folder's headers.
# A folder with headers only becomes an INTERFACE library. Every module is installed and exported
# as avar::NAME (cmake/AvarPackage.cmake); the project's warning flags stay in the build tree.
function(avar_module name)
  cmake_parse_arguments(ARG "" "FOLDER" "SOURCES;DEPS" ${ARGN})
  set(include_dir ${CMAKE_CURRENT_SOURCE_DIR}/include)
  if(ARG_FOLDER)
    set(include_dir ${CMAKE_CURRENT_SOURCE_DIR}/${ARG_FOLDER}/include)
  endif()
  if(ARG_SOURCES)
    add_library(avar_${name} STATIC ${ARG_SOURCES})
    target_include_directories(avar_${name} PUBLIC $<BUILD_INTERFACE:${include_dir}>
                                                   $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(avar_${name} PUBLIC ${ARG_DEPS} PRIVATE $<BUILD_INTERFACE:avar_build_flags>)
  else()
    add_library(avar_${name} INTERFACE)
    target_include_directories(avar_${name} INTERFACE $<BUILD_INTERFACE:${include_dir}>
                                                      $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
    target_link_libraries(avar_${name} INTERFACE ${ARG_DEPS})
  endif()
  add_library(avar::${name} ALIAS avar_${name})
  avar_install_library(avar_${name} ${name} ${include_dir})
endfunction()

# avar_test(NAME SOURCES ... DEPS ...) builds one GoogleTest executable and registers its tests.
function(avar_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  # Test files are compiled eight to a unit: each one alone spent most of its time on the same
  # GoogleTest and Eigen headers (file-local names must therefore differ between a module's tests).
  set_target_properties(${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main avar_build_flags)
  target_compile_definitions(${name} PRIVATE
    AVAR_SOURCE_DIR="${PROJECT_SOURCE_DIR}" AVAR_TEST_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data")
  # 300 s: the seeded property families (10^5 cases) take up to half a minute in the sanitizer build,
  # more on a loaded machine.
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 30 PROPERTIES TIMEOUT 300)
endfunction()
