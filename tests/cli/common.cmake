# Helpers shared by the CLI scripts that ctest runs with `cmake -P` (each is given
# -DFACESKETCH=<exe> and -DWORK=<dir>): include(${CMAKE_CURRENT_LIST_DIR}/common.cmake).

# run_command(CMD ARGS...): runs any command; a non-zero exit or a Vulkan validation message
# fails the test. Sets `out` to its standard output (also logged, shown when a test fails).
function(run_command)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN} failed (${rc}): ${out} ${err}")
  endif()
  if(err MATCHES "validation")
    message(FATAL_ERROR "validation messages: ${err}")
  endif()
  message(STATUS "${out}")
  set(out "${out}" PARENT_SCOPE)
endfunction()

# run(ARGS...): run_command(${FACESKETCH} ARGS...).
function(run)
  run_command(${FACESKETCH} ${ARGN})
  set(out "${out}" PARENT_SCOPE)
endfunction()

# expect_failure(PATTERN ARGS...): `facesketch ARGS...` must exit with code 1 and print a
# message matching PATTERN on standard error.
function(expect_failure pattern)
  execute_process(COMMAND ${FACESKETCH} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "facesketch ${ARGN}: expected exit code 1, got ${rc}: ${out} ${err}")
  endif()
  if(NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "facesketch ${ARGN}: expected a message matching '${pattern}', got: ${err}")
  endif()
endfunction()
