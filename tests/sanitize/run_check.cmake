# tests/sanitize/run_check.cmake — the unit tests and the validation cases are clean under
# AddressSanitizer (with LeakSanitizer) and UBSan. Run by ctest (test sanitized_unit_and_validation,
# label sanitize) from a normal build as
#   cmake -DSOURCE_DIR=<nscd source> -DWORK_DIR=<scratch> -DTARGETS="a;b" -DLABELS=<regex>
#         [-DEXCLUDE_LABELS=<regex>] [-DJOBS=2] -P run_check.cmake
# Steps: configure <SOURCE_DIR> into <WORK_DIR> with -DNSCD_SANITIZE=address,undefined at
# -O1 -g1 (asserts on; examples and benchmarks off), build only TARGETS, run the ctest tests whose
# label matches LABELS (and not EXCLUDE_LABELS) with halt_on_error=1 for both sanitizers. Any
# failing test fails this one, and so does any sanitizer report found in the tests' log (a report
# in a child process that the test let pass). The whole suite by hand: docs/user-guide.md §1.1.
cmake_minimum_required(VERSION 3.25)
set(CHECK_NAME "sanitize run_check")
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/check_steps.cmake")  # check_required, run_step, nested_configure
check_required(SOURCE_DIR WORK_DIR TARGETS LABELS)
if(NOT DEFINED JOBS)
  set(JOBS 2)
endif()
set(exclude "")
if(DEFINED EXCLUDE_LABELS AND NOT EXCLUDE_LABELS STREQUAL "")
  set(exclude -LE "${EXCLUDE_LABELS}")
endif()

string(TIMESTAMP t0 "%s")
file(MAKE_DIRECTORY "${WORK_DIR}")
nested_configure("${WORK_DIR}" -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1"
  -DNSCD_SANITIZE=address,undefined -DNSCD_BUILD_EXAMPLES=OFF)
string(FIND "${step_output}" "nscd: sanitizers address,undefined" found)
if(found EQUAL -1)
  message(FATAL_ERROR "sanitize run_check: the configure step did not turn the sanitizers on:\n${step_output}")
endif()
run_step("build" ${CMAKE_COMMAND} --build "${WORK_DIR}" --target ${TARGETS} -j ${JOBS})
string(TIMESTAMP t1 "%s")

# halt_on_error: the first report ends the program with a non-zero status. Leak checks stay on
# (detect_leaks=1, ASan's default on Linux). print_stacktrace: UBSan reports say where.
set(env ASAN_OPTIONS=halt_on_error=1:detect_leaks=1
        UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1)
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env}
    ${CMAKE_CTEST_COMMAND} --test-dir "${WORK_DIR}" -L "${LABELS}" ${exclude} -j ${JOBS} --output-on-failure
      --no-tests=error
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(TIMESTAMP t2 "%s")
set(log "${WORK_DIR}/Testing/Temporary/LastTest.log")
set(reports "")
if(EXISTS "${log}")
  file(STRINGS "${log}" reports REGEX "ERROR: (Address|Leak)Sanitizer|runtime error: ")
endif()
if(NOT rc EQUAL 0 OR reports)
  list(JOIN reports "\n" reports)
  message(FATAL_ERROR "sanitize run_check: the sanitized tests failed (ctest exit ${rc})\n"
    "--- sanitizer reports in ${log} ---\n${reports}\n--- ctest output ---\n${out}\n${err}")
endif()
string(REGEX MATCH "[0-9]+% tests passed[^\n]*" summary "${out}")
math(EXPR build_s "${t1} - ${t0}")
math(EXPR run_s "${t2} - ${t1}")
message(STATUS "sanitize run_check: ${summary} under ASan+UBSan (configure+build ${build_s} s, tests ${run_s} s)")
