# The warnings every fibermold target compiles with (fibermold_warnings(TARGET)), errors with
# FIBERMOLD_WARNINGS_AS_ERRORS.
function(fibermold_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra $<$<BOOL:${FIBERMOLD_WARNINGS_AS_ERRORS}>:-Werror>)
endfunction()

# fibermold_module(NAME SOURCES ... [PUBLIC deps...] [PRIVATE deps...])
# One static library per module folder, target fibermold_<NAME>, alias fibermold::<NAME>.
# Headers are included as "<module>/<file>.hpp" from the source root.
function(fibermold_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(fibermold_${name} STATIC ${M_SOURCES})
  add_library(fibermold::${name} ALIAS fibermold_${name})
  target_include_directories(fibermold_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  fibermold_warnings(fibermold_${name})
  target_link_libraries(fibermold_${name} PUBLIC ${M_PUBLIC} PRIVATE ${M_PRIVATE})
endfunction()

# fibermold_test(NAME SOURCES ... LIBS ...): a GoogleTest executable registered with ctest.
function(fibermold_test name)
  cmake_parse_arguments(T "" "" "SOURCES;LIBS;PROPERTIES" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  fibermold_warnings(${name})
  target_link_libraries(${name} PRIVATE ${T_LIBS} fibermold_test_support GTest::gmock GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    FIBERMOLD_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    FIBERMOLD_BINARY="$<TARGET_FILE:fibermold>")
  # A test that hangs fails after 5 minutes instead of stalling CI.
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300 ${T_PROPERTIES})
endfunction()
