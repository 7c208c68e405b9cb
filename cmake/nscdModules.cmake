# nscd_add_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One library per src/ folder (static; shared with BUILD_SHARED_LIBS=ON), target nscd_<name>,
# alias nscd::<name>, exported as nscd::<name>. Dependencies between modules are written here, one way only.
function(nscd_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(nscd_${name} ${ARG_SOURCES})
  add_library(nscd::${name} ALIAS nscd_${name})
  set_target_properties(nscd_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME nscd_${name})
  target_include_directories(nscd_${name} PUBLIC
    $<BUILD_INTERFACE:${NSCD_BUILD_INCLUDE}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(nscd_${name} PUBLIC cxx_std_20)
  nscd_warnings(nscd_${name})
  target_link_libraries(nscd_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  # A sanitized library needs the sanitizer runtimes wherever it is linked (installed too).
  target_link_options(nscd_${name} INTERFACE ${NSCD_SANITIZE_LINK_FLAGS})
  install(TARGETS nscd_${name} EXPORT nscdTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

function(nscd_warnings target)
  # -Wno-restrict: GCC 12 false positive on std::string concatenation (GCC bug 105651)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  # without OpenMP its pragmas are ignored on purpose (the loops run on one thread)
  if(NOT NSCD_WITH_OPENMP)
    target_compile_options(${target} PRIVATE -Wno-unknown-pragmas)
  endif()
endfunction()

# nscd_add_driver_test(<name> COMMAND <exe> [args...] SUMMARY <dir>/summary.txt KEYS <k1;k2;...>)
# A smoke test of a driver: <name>_run runs it (a fixture), <name>_summary_keys checks that its
# summary file has every key as "key = <number>" (cmake/check_summary.cmake).
function(nscd_add_driver_test name)
  cmake_parse_arguments(ARG "" "SUMMARY" "COMMAND;KEYS" ${ARGN})
  add_test(NAME ${name}_run COMMAND ${ARG_COMMAND})
  add_test(NAME ${name}_summary_keys COMMAND ${CMAKE_COMMAND} -DFILE=${ARG_SUMMARY} "-DKEYS=${ARG_KEYS}"
    -P ${PROJECT_SOURCE_DIR}/cmake/check_summary.cmake)
  set_tests_properties(${name}_run PROPERTIES FIXTURES_SETUP ${name} LABELS examples TIMEOUT 300)
  set_tests_properties(${name}_summary_keys PROPERTIES FIXTURES_REQUIRED ${name} LABELS examples)
endfunction()

# nscd_test_program(<target>): how a test program that times nothing is compiled. Its sources
# are compiled together in batches (a unity build: the headers are parsed once per batch, not
# once per file) and, in an optimized build, at -O1: the code under test is in the nscd libraries,
# which keep the build type's flags; the test files only set up scenes, call it and compare.
# NSCD_FAST_TEST_BUILD=OFF compiles them file by file with the build type's flags.
function(nscd_test_program target)
  if(NOT NSCD_FAST_TEST_BUILD)
    return()
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  # -Wsubobject-linkage: GCC warns on a test fixture of an anonymous namespace once the file is
  # included in the batch's source rather than compiled as the main file
  target_compile_options(${target} PRIVATE $<$<CONFIG:Release,RelWithDebInfo,MinSizeRel>:-O1>
    $<$<CXX_COMPILER_ID:GNU>:-Wno-subobject-linkage>)
endfunction()

# nscd_unity_program(<target>): a target of several files outside src/ (a driver, a driver's
# library, nscd::scenes, nscd::driver, the extremes suite) compiled as one translation unit with
# the build type's flags, because parsing the headers is most of its files' compile time.
# BATCHES n splits it into n units of about equal file counts instead. NSCD_UNITY_BUILD=OFF
# compiles its files one by one.
function(nscd_unity_program target)
  cmake_parse_arguments(ARG "" "BATCHES" "" ${ARGN})
  if(NOT NSCD_UNITY_BUILD)
    return()
  endif()
  set(batch_size 0)
  if(ARG_BATCHES)
    get_target_property(sources ${target} SOURCES)
    list(LENGTH sources count)
    math(EXPR batch_size "(${count} + ${ARG_BATCHES} - 1) / ${ARG_BATCHES}")
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${batch_size})
endfunction()
