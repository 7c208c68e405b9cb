# tests/install/run_install_check.cmake — the installed package works for a researcher's own
# driver. Run by ctest (test install_and_build_out_of_tree_driver) as
#   cmake -DNSCD_BUILD_DIR=<nscd build> -DCONSUMER_SOURCE_DIR=<tests/install>
#         -DWORK_DIR=<scratch> -P run_install_check.cmake
# Steps: install the built nscd into <WORK_DIR>/prefix; check the headers and the CMake
# package are there; check the drivers are in bin/ and answer --help (and that stiffness_study
# finds the installed ballast next to itself), when the build has the examples; configure
# tests/install/ against that prefix only; build it; run the driver and check its exit status and
# output (consumer_check.cmake). Any failure stops with the command's output.
cmake_minimum_required(VERSION 3.25)

set(CHECK_NAME run_install_check)
include("${CMAKE_CURRENT_LIST_DIR}/consumer_check.cmake")  # check_required, run_step, build_and_run_consumer
check_required(NSCD_BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR)
if(NOT EXISTS "${NSCD_BUILD_DIR}/CMakeCache.txt")
  message(FATAL_ERROR "run_install_check: ${NSCD_BUILD_DIR} is not a configured nscd build directory")
endif()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/build")

# The nscd build's settings, so the driver is built with the same compiler and build type.
function(read_cache name out)
  file(STRINGS "${NSCD_BUILD_DIR}/CMakeCache.txt" line REGEX "^${name}:[A-Z]+=")
  string(REGEX REPLACE "^${name}:[A-Z]+=" "" value "${line}")
  set(${out} "${value}" PARENT_SCOPE)
endfunction()
read_cache(CMAKE_CXX_COMPILER cxx)
read_cache(CMAKE_BUILD_TYPE build_type)
read_cache(CMAKE_GENERATOR generator)
read_cache(CMAKE_HOME_DIRECTORY source_dir)
if(build_type STREQUAL "")
  set(build_type Release)
endif()

# 1. Fresh scratch directory and install.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
run_step("install" ${CMAKE_COMMAND} --install "${NSCD_BUILD_DIR}" --prefix "${prefix}")

# 2. The install tree: every public header at include/nscd/<module>/ and
#    include/nscd/shared/, and the CMake package.
file(GLOB_RECURSE src_headers RELATIVE "${source_dir}/src" "${source_dir}/src/*.hpp")
file(GLOB_RECURSE shared_headers RELATIVE "${source_dir}/shared" "${source_dir}/shared/*.hpp")  # driver/ too
set(expected "")
foreach(h ${src_headers})
  list(APPEND expected "include/nscd/${h}")
endforeach()
foreach(h ${shared_headers})
  list(APPEND expected "include/nscd/shared/${h}")
endforeach()
if(NOT src_headers)
  message(FATAL_ERROR "run_install_check: no header found under ${source_dir}/src")
endif()
foreach(h ${expected})
  if(NOT EXISTS "${prefix}/${h}")
    message(FATAL_ERROR "run_install_check: ${h} is missing from the install tree ${prefix}")
  endif()
endforeach()
file(GLOB_RECURSE config_files "${prefix}/*/nscdConfig.cmake")
if(NOT config_files)
  message(FATAL_ERROR "run_install_check: no nscdConfig.cmake under ${prefix}")
endif()
list(LENGTH expected n_headers)
message(STATUS "install tree: ${n_headers} headers, ${config_files}")

# 2b. The drivers, installed in bin/ when the nscd build has them (NSCD_BUILD_EXAMPLES): each
#     answers --help with status 0, and stiffness_study finds bin/ballast next to itself.
read_cache(NSCD_BUILD_EXAMPLES build_examples)
if(build_examples)
  set(drivers ballast deposit lmgc90_deposit_case stiffness_study accuracy_study solver_comparison scaling scene_demo settle_demo biaxial drum
    datbox_run)
  foreach(d ${drivers})
    if(NOT EXISTS "${prefix}/bin/${d}")
      message(FATAL_ERROR "run_install_check: the driver bin/${d} is missing from the install tree ${prefix}")
    endif()
    run_step("${d} --help" "${prefix}/bin/${d}" --help)
    if(NOT step_output MATCHES "--help|Options|options")
      message(FATAL_ERROR "run_install_check: bin/${d} --help printed no option list:\n${step_output}")
    endif()
  endforeach()
  run_step("stiffness_study --dry-run" "${prefix}/bin/stiffness_study" --dry-run --samples 1 --k-factors 1 --cycles 1
    --output "${WORK_DIR}/study_dry_run")
  string(FIND "${step_output}" "${prefix}/bin/ballast" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "run_install_check: the installed stiffness_study does not run the installed ${prefix}/bin/ballast:\n${step_output}")
  endif()
  list(LENGTH drivers n_drivers)
  message(STATUS "install tree: ${n_drivers} drivers in bin/, each answers --help")
endif()

# 3. Configure and build the consumer against the prefix only; run its drivers.
build_and_run_consumer("${prefix}" "${CONSUMER_SOURCE_DIR}" "${consumer_build}" "${generator}" "${build_type}" "${cxx}")
