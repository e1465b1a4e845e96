# Small helpers shared by every CMakeLists.txt in the tree.

# facesketch_add_library(NAME SOURCES... [DEPS targets...])
# A static library for one engine folder; its headers are included as "folder/file.h".
function(facesketch_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/engine)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
endfunction()

# facesketch_add_test(NAME SOURCES... [DEPS targets...])
# One Catch2 executable per engine folder; every TEST_CASE becomes its own CTest test,
# run in its own process so a Vulkan validation message fails exactly the test that caused it.
function(facesketch_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE facesketch_test_main ${ARG_DEPS})
  if(FACESKETCH_UNITY_TESTS)
    set_target_properties(${name} PROPERTIES UNITY_BUILD ON)
  endif()
  # --warn NoTests: a ctest entry whose name matches no test case fails instead of passing
  # with nothing run (a ';' in a test name once split two names and silently ran nothing).
  catch_discover_tests(${name}
    EXTRA_ARGS --warn NoTests
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES ENVIRONMENT "FACESKETCH_VALIDATION=1;FACESKETCH_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
