# driveid_add_test(NAME source...): one Catch2 test executable per component,
# linked with the shared Catch2 main, registered with CTest.
function(driveid_add_test name)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE driveid driveid_test_main driveid_warnings fmt::fmt)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  add_test(NAME ${name} COMMAND ${name})
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "DRIVEID_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
