# tests/no_suitesparse/run_check.cmake — a build without SuiteSparse (NEWTON_AC off) still
# builds and passes its tests. Run by ctest (test build_without_suitesparse) as
#   cmake -DSOURCE_DIR=<nscd source> -DWORK_DIR=<scratch> -P run_check.cmake
# Steps: configure <SOURCE_DIR> into <WORK_DIR> with -DNSCD_WITH_SUITESPARSE=OFF (examples and
# benchmarks off, to keep it short), build the unit tests and the validation cases, run them.
# Run from a sanitized build (NSCD_SANITIZE), it builds with the same sanitizers and flags.
# The NEWTON_AC tests skip there, and NewtonACUnavailable checks the clear error message.
cmake_minimum_required(VERSION 3.25)
set(CHECK_NAME run_check)
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/check_steps.cmake")  # check_required, run_step, nested_configure
check_required(SOURCE_DIR WORK_DIR)

# From a sanitized build (-DSANITIZE=address,undefined, passed by tests/CMakeLists.txt with the
# outer build's type and flags), this build is sanitized the same way; otherwise it is Release.
set(build_options -DCMAKE_BUILD_TYPE=Release)
if(DEFINED SANITIZE AND NOT SANITIZE STREQUAL "" AND NOT SANITIZE MATCHES "^(OFF|Off|off|NO|no|FALSE|false|0)$")
  string(TOUPPER "${BUILD_TYPE}" type_upper)
  set(build_options "-DNSCD_SANITIZE=${SANITIZE}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_CXX_FLAGS_${type_upper}=${CXX_FLAGS_BUILD_TYPE}")
endif()

file(MAKE_DIRECTORY "${WORK_DIR}")
nested_configure("${WORK_DIR}" ${build_options} -DNSCD_WITH_SUITESPARSE=OFF -DNSCD_BUILD_EXAMPLES=OFF)
string(FIND "${step_output}" "NEWTON_AC (SuiteSparse KLU) OFF" found)
if(found EQUAL -1)
  message(FATAL_ERROR "run_check: the configure step did not report NEWTON_AC off:\n${step_output}")
endif()
run_step("build" ${CMAKE_COMMAND} --build "${WORK_DIR}" --target nscd_unit_tests nscd_validation -j 2)
# No library of this build may link SuiteSparse.
file(GLOB_RECURSE link_files "${WORK_DIR}/src/*link.txt")
foreach(f ${link_files})
  file(READ "${f}" text)
  if(text MATCHES "klu")
    message(FATAL_ERROR "run_check: ${f} links KLU in a build without SuiteSparse")
  endif()
endforeach()
run_step("unit tests" "${WORK_DIR}/tests/nscd_unit_tests" --gtest_brief=1)
run_step("validation" "${WORK_DIR}/validation/nscd_validation" --gtest_brief=1)
message(STATUS "run_check: the build without SuiteSparse passed its unit tests and validation cases")
