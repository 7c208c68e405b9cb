# tests/cmake/check_steps.cmake — the steps the build checks run as `cmake -P` scripts share
# (../install/, ../shared_libs/, ../no_suitesparse/, ../sanitize/). Set CHECK_NAME (the name their
# messages start with) before including it.

# Stops unless every variable named is set and not empty (the script's -D arguments).
function(check_required)
  foreach(var ${ARGN})
    if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
      message(FATAL_ERROR "${CHECK_NAME}: ${var} is not set")
    endif()
  endforeach()
endfunction()

# Runs a command; on failure stops with its output. `step` names it in the message; the command's
# stdout and stderr are left in step_output.
function(run_step step)
  execute_process(COMMAND ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    string(REPLACE ";" " " cmd "${ARGN}")
    message(FATAL_ERROR "${CHECK_NAME}: ${step} failed (exit ${rc})\n"
      "command: ${cmd}\n--- stdout ---\n${out}\n--- stderr ---\n${err}")
  endif()
  set(step_output "${out}${err}" PARENT_SCOPE)
endfunction()

# nested_configure(<build dir> <cache options...>): configures SOURCE_DIR into <build dir>,
# benchmarks off (no check needs them), with GENERATOR and LAUNCHER (the outer build's generator
# and compiler launcher) when the script was given them. Its output is left in step_output.
function(nested_configure build)
  set(generator)
  if(DEFINED GENERATOR AND NOT GENERATOR STREQUAL "")
    set(generator -G "${GENERATOR}")
  endif()
  set(launcher)
  if(DEFINED LAUNCHER AND NOT LAUNCHER STREQUAL "")
    set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
  endif()
  run_step("configure" ${CMAKE_COMMAND} -S "${SOURCE_DIR}" -B "${build}" ${generator} ${launcher}
    -DNSCD_BUILD_BENCHMARKS=OFF ${ARGN})
  set(step_output "${step_output}" PARENT_SCOPE)
endfunction()
