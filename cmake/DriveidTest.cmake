# driveid_add_test(NAME source...): one Catch2 test executable per component,
# linked with the shared Catch2 main, registered with CTest.
# The tests share one precompiled header (Catch2, Eigen, fmt), made by
# driveid_test_pch, whose flags are a test's flags: neither is compiled with
# CMake's position-independent flags (a library's -fPIC and an executable's
# -fPIE would differ; the compiler's default, PIE on Debian, is the same).
add_library(driveid_test_pch OBJECT ${PROJECT_SOURCE_DIR}/tests/support/precompiled.cc)
set_target_properties(driveid_test_pch PROPERTIES POSITION_INDEPENDENT_CODE OFF)
target_link_libraries(driveid_test_pch PRIVATE driveid driveid_test_main driveid_warnings fmt::fmt)
target_include_directories(driveid_test_pch PRIVATE ${PROJECT_SOURCE_DIR}/tests)
target_compile_options(driveid_test_pch PRIVATE $<$<CONFIG:Release>:-O1>)
driveid_precompile(driveid_test_pch ${DRIVEID_PCH_STD} <catch2/catch.hpp> <Eigen/Dense> <fmt/format.h>)

function(driveid_add_test name)
  add_executable(${name} ${ARGN})
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE OFF)
  driveid_precompile_reuse(${name} driveid_test_pch)
  target_link_libraries(${name} PRIVATE driveid driveid_test_main driveid_warnings fmt::fmt)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  # A test's own file is checks and set-up at -O1 in Release (Catch2's
  # assertion macros at -O3 cost a third more compile time and no run time);
  # the library and the generators (driveid_test_support) stay at -O3.
  target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O1>)
  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "DRIVEID_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
