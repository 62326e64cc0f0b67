# avar_module(NAME SOURCES ... DEPS ...) declares the library of one top-level folder:
# target avar_NAME, alias avar::NAME, public headers under NAME/include/avar/NAME/.
# A folder with headers only becomes an INTERFACE library.
function(avar_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  if(ARG_SOURCES)
    add_library(avar_${name} STATIC ${ARG_SOURCES})
    target_include_directories(avar_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
    target_link_libraries(avar_${name} PUBLIC ${ARG_DEPS} PRIVATE avar_build_flags)
  else()
    add_library(avar_${name} INTERFACE)
    target_include_directories(avar_${name} INTERFACE ${CMAKE_CURRENT_SOURCE_DIR}/include)
    target_link_libraries(avar_${name} INTERFACE ${ARG_DEPS})
  endif()
  add_library(avar::${name} ALIAS avar_${name})
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
