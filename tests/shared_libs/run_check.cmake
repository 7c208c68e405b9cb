# tests/shared_libs/run_check.cmake — a build with shared libraries (-DBUILD_SHARED_LIBS=ON)
# links, installs and runs. Run by ctest (test build_shared_libs) as
#   cmake -DSOURCE_DIR=<nscd source> -DWORK_DIR=<scratch> [-DGENERATOR=Ninja] [-DLAUNCHER=ccache]
#         -P run_check.cmake
# Steps: configure <SOURCE_DIR> into <WORK_DIR>/build with shared libraries linked with
# -Wl,--no-undefined (every library names the libraries it uses), the tests and benchmarks off;
# build the libraries and one driver (datbox_run); install them into <WORK_DIR>/prefix; delete the
# build tree, so that only the installed libraries can be found; check that the installed driver
# finds them through its RPATH and runs a small DATBOX case; build tests/install/ against the
# prefix and run its drivers (../install/consumer_check.cmake). Any failure stops with the output.
cmake_minimum_required(VERSION 3.25)
set(CHECK_NAME run_check)
include("${CMAKE_CURRENT_LIST_DIR}/../install/consumer_check.cmake")  # check_required, run_step, nested_configure, …
check_required(SOURCE_DIR WORK_DIR)

set(build "${WORK_DIR}/build")
set(prefix "${WORK_DIR}/prefix")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# 1. Configure and build the libraries and datbox_run (which links every one of them), with the
#    outer build's generator and compiler launcher.
if(NOT DEFINED GENERATOR OR GENERATOR STREQUAL "")
  set(GENERATOR "Unix Makefiles")
endif()
nested_configure("${build}" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON
  "-DCMAKE_SHARED_LINKER_FLAGS=-Wl,--no-undefined" -DNSCD_BUILD_TESTS=OFF -DNSCD_BUILD_EXAMPLES=ON)
file(STRINGS "${build}/CMakeCache.txt" cxx REGEX "^CMAKE_CXX_COMPILER:[A-Z]+=")
string(REGEX REPLACE "^CMAKE_CXX_COMPILER:[A-Z]+=" "" cxx "${cxx}")
set(libraries core laws bodies contactors interactions solvers io scenes driver)
list(TRANSFORM libraries PREPEND nscd_ OUTPUT_VARIABLE library_targets)
run_step("build" ${CMAKE_COMMAND} --build "${build}" --target ${library_targets} datbox_run -j 2)

# 2. Install the libraries, headers and package (component Unspecified) and the one driver.
run_step("install the libraries" ${CMAKE_COMMAND} --install "${build}" --prefix "${prefix}" --component Unspecified)
run_step("install datbox_run" ${CMAKE_COMMAND} --install "${build}" --prefix "${prefix}" --component datbox_run)
file(REMOVE_RECURSE "${build}")
file(GLOB static_libraries "${prefix}/*/libnscd_*.a")
if(static_libraries)
  message(FATAL_ERROR "run_check: a shared build installed static libraries: ${static_libraries}")
endif()

# Stops unless <executable> loads each of the nscd libraries <names...> from the prefix, found
# as the loader finds them (RUNPATH), not through the build tree, which is gone.
function(check_loads_from_prefix executable)
  file(GET_RUNTIME_DEPENDENCIES EXECUTABLES "${executable}" RESOLVED_DEPENDENCIES_VAR resolved
    UNRESOLVED_DEPENDENCIES_VAR unresolved PRE_INCLUDE_REGEXES "^libnscd_" PRE_EXCLUDE_REGEXES ".*")
  set(paths)  # bin/../lib/../lib/x.so (the RUNPATH at each level) as lib/x.so
  foreach(path ${resolved})
    file(REAL_PATH "${path}" path)
    list(APPEND paths "${path}")
  endforeach()
  file(REAL_PATH "${prefix}" real_prefix)
  foreach(lib ${ARGN})
    set(found "${paths}")
    list(FILTER found INCLUDE REGEX "^${real_prefix}/[^/]+/libnscd_${lib}\\.so$")
    if(NOT found)
      message(FATAL_ERROR "run_check: ${executable} does not load libnscd_${lib}.so from ${prefix}\n"
        "resolved: ${resolved}\nunresolved: ${unresolved}")
    endif()
  endforeach()
endfunction()

# 3. The installed driver finds every nscd library in the prefix (its RPATH) and runs.
set(driver "${prefix}/bin/datbox_run")
check_loads_from_prefix("${driver}" ${libraries})
run_step("run the installed datbox_run" "${driver}" --datbox "${SOURCE_DIR}/tests/data/datbox/disks_jcbox"
  --steps 20 --output-every 10 --output "${WORK_DIR}/datbox_run")
if(NOT step_output MATCHES "datbox_run: 20 steps to t = " OR NOT EXISTS "${WORK_DIR}/datbox_run/final.nscd")
  message(FATAL_ERROR "run_check: the installed datbox_run did not run 20 steps:\n${step_output}")
endif()

# 4. A researcher's own drivers built against the installed shared libraries.
build_and_run_consumer("${prefix}" "${SOURCE_DIR}/tests/install" "${WORK_DIR}/consumer" "${GENERATOR}" Release "${cxx}")
check_loads_from_prefix("${WORK_DIR}/consumer/toolkit_driver" ${libraries})
message(STATUS "run_check: the shared build installed, and its drivers and the consumer's ran")
