# beltsim_gtest_suites(PROGRAM LABEL label TIMEOUT seconds [COSTS Suite:seconds...]): one CTest
# test per GoogleTest suite of PROGRAM (named PROGRAM.Suite, running --gtest_filter=Suite.*), listed
# when ctest starts, as gtest_discover_tests(... DISCOVERY_MODE PRE_TEST) lists one per test. One
# process a suite instead of one a test: under ASan + UBSan each start of a test program (its
# relocations, the sanitizers' start, LeakSanitizer's scan at exit) takes about 0.17 s of CPU, and
# the quick programs have 384 tests (docs/testing.md). A program that was not built, or does not
# list its tests, shows as one failing test, PROGRAM_NOT_BUILT, with the label.
function(beltsim_gtest_suites program)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "LABEL;TIMEOUT" "COSTS")
  set(script ${CMAKE_CURRENT_BINARY_DIR}/${program}_suites.cmake)
  file(GENERATE OUTPUT ${script} CONTENT
"set(program \"$<TARGET_FILE:${program}>\")
set(name ${program})
set(label ${arg_LABEL})
set(timeout ${arg_TIMEOUT})
set(costs \"${arg_COSTS}\")
include(\"${PROJECT_SOURCE_DIR}/cmake/gtest_suites_add.cmake\")
")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${script})
endfunction()
