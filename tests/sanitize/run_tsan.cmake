# tests/sanitize/run_tsan.cmake — the unit tests, the threaded ones among them, are free of data
# races under ThreadSanitizer. Run by ctest (test threads_under_tsan, labels sanitize and slow) as
#   cmake -DSOURCE_DIR=<nscd source> -DWORK_DIR=<scratch> -DCLANGXX=<clang++> -DCLANG=<clang>
#         -DARCHER=<libarcher.so> -DFILTER=<gtest filter> [-DJOBS=2] -P run_tsan.cmake
# Steps: configure <SOURCE_DIR> into <WORK_DIR> with Clang and -DNSCD_SANITIZE=thread at -O1 -g1
# (examples off), build nscd_unit_tests, run the tests FILTER selects in one process with Archer
# (OMP_TOOL_LIBRARIES), which tells TSan what OpenMP's own barriers order. Any report, or any
# failing test, fails this one. By hand: docs/user-guide.md §1.2.
cmake_minimum_required(VERSION 3.25)
set(CHECK_NAME "tsan run_tsan")
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/check_steps.cmake")  # check_required, run_step, nested_configure
check_required(SOURCE_DIR WORK_DIR CLANGXX CLANG ARCHER FILTER)
if(NOT DEFINED JOBS)
  set(JOBS 2)
endif()

string(TIMESTAMP t0 "%s")
file(MAKE_DIRECTORY "${WORK_DIR}")
nested_configure("${WORK_DIR}" -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1"
  "-DCMAKE_CXX_COMPILER=${CLANGXX}" "-DCMAKE_C_COMPILER=${CLANG}" -DNSCD_SANITIZE=thread -DNSCD_BUILD_EXAMPLES=OFF)
string(FIND "${step_output}" "nscd: sanitizers thread" found)
if(found EQUAL -1)
  message(FATAL_ERROR "tsan run_tsan: the configure step did not turn ThreadSanitizer on:\n${step_output}")
endif()
run_step("build" ${CMAKE_COMMAND} --build "${WORK_DIR}" --target nscd_unit_tests -j ${JOBS})
string(TIMESTAMP t1 "%s")

# exitcode: TSan's status for a run that reported (66 by default), set here so that it is known
set(env "OMP_TOOL_LIBRARIES=${ARCHER}"
        "TSAN_OPTIONS=halt_on_error=0:exitcode=66:report_signal_unsafe=0:suppressions=${CMAKE_CURRENT_LIST_DIR}/tsan.supp")
find_program(unit_tests nscd_unit_tests PATHS "${WORK_DIR}/tests" NO_DEFAULT_PATH REQUIRED)
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} ARCHER_OPTIONS=verbose=1
    "${unit_tests}" "--gtest_filter=${FILTER}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(TIMESTAMP t2 "%s")
file(WRITE "${WORK_DIR}/tsan.log" "${out}\n${err}")
string(REGEX MATCHALL "WARNING: ThreadSanitizer[^\n]*" reports "${err}")
string(FIND "${out}" "Archer detected OpenMP application with TSan" archer)
string(REGEX MATCH "\\[==========\\] [0-9]+ tests from [0-9]+ test suites ran" ran "${out}")
if(NOT rc EQUAL 0 OR reports OR archer EQUAL -1 OR NOT ran)
  list(LENGTH reports n)
  set(why "exit ${rc}, ${n} ThreadSanitizer reports")
  if(archer EQUAL -1)
    string(APPEND why "; Archer was not loaded (OMP_TOOL_LIBRARIES=${ARCHER})")
  endif()
  string(SUBSTRING "${err}" 0 6000 head)
  message(FATAL_ERROR "tsan run_tsan: ${why}; the whole log: ${WORK_DIR}/tsan.log\n${head}\n${out}")
endif()
math(EXPR build_s "${t1} - ${t0}")
math(EXPR run_s "${t2} - ${t1}")
message(STATUS "tsan run_tsan: ${ran} under ThreadSanitizer, no report (configure+build ${build_s} s, tests ${run_s} s)")
