# Shared helpers for the layer CMakeLists.

# Warnings used by every target of the project.
function(ffr_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-unused-parameter)
endfunction()

# Precompiled headers: the third-party headers (Eigen, GoogleTest, nlohmann-json) take most of the
# parsing of a typical source here (a runtime test: 3.3 of its 4.7 CPU-s at -O3), so each library
# (with its own most included header, the runtime's data.hpp) and the test suite parse them once
# (tools/bench/compile/RESULTS.md). A source whose macros or optimisation flags must differ from
# the header's opts out with SKIP_PRECOMPILE_HEADERS; -DFFR_PCH=OFF builds without (each source
# then proves it includes what it uses).
option(FFR_PCH "Precompile the most included headers once per library and once for the tests" ON)
function(ffr_precompile_headers target)
  if(FFR_PCH)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# ffr_library(NAME ALIAS_NAME SOURCE_DIR) : a library whose sources are every *.cpp under SOURCE_DIR.
# New files are picked up on the next build (CONFIGURE_DEPENDS), so parallel work only adds files.
function(ffr_glob_sources out dir)
  file(GLOB_RECURSE srcs CONFIGURE_DEPENDS ${dir}/*.cpp ${dir}/*.c)
  set(${out} ${srcs} PARENT_SCOPE)
endfunction()

# ffr_test(NAME SOURCES... LIBS libs... [LABELS labels...] [TIMEOUT s])
# One GoogleTest executable, registered with gtest_discover_tests, run from the test's own source dir.
function(ffr_test name)
  cmake_parse_arguments(T "" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    FFR_SOURCE_DIR="${PROJECT_SOURCE_DIR}" FFR_BINARY_DIR="${PROJECT_BINARY_DIR}")
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  ffr_warnings(${name})
  if(FFR_PCH)
    target_precompile_headers(${name} REUSE_FROM ffr_test_pch)  # tests/CMakeLists.txt
  endif()
  # The sanitizer pass runs no test labelled slow (scripts/sanitize/README.md): not built there.
  if(FFR_SANITIZE AND "slow" IN_LIST T_LABELS)
    set_target_properties(${name} PROPERTIES EXCLUDE_FROM_ALL TRUE)
    return()
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  # The labels are set by a script of their own, run by ctest after the discovered tests are
  # added: passed in PROPERTIES, a list "a;b" reaches set_tests_properties as the value a and a
  # property named b, and every label after the first is lost.
  gtest_discover_tests(${name} WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}
    PROPERTIES TIMEOUT ${T_TIMEOUT} DISCOVERY_TIMEOUT 60 TEST_LIST ${name}_TESTS)
  set(script "${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake")
  file(WRITE "${script}" "if(${name}_TESTS)\n  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${T_LABELS}\")\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${script}")
endfunction()
