# tests/install/consumer_check.cmake — the steps shared by the checks of an installed nscd
# (run_install_check.cmake, ../shared_libs/run_check.cmake). Set CHECK_NAME (the name their
# messages start with) before including it.

include("${CMAKE_CURRENT_LIST_DIR}/../cmake/check_steps.cmake")  # check_required, run_step

# build_and_run_consumer(<prefix> <consumer source> <consumer build> <generator> <build type> <C++ compiler>)
# Configures the consumer project (tests/install/) against <prefix> only (the package registry is
# not consulted, so only the installed package can satisfy find_package), builds it, runs its two
# drivers and checks what they print.
function(build_and_run_consumer prefix source build generator build_type cxx)
  run_step("configure the consumer project"
    ${CMAKE_COMMAND} -S "${source}" -B "${build}" -G "${generator}" "-DCMAKE_PREFIX_PATH=${prefix}"
      "-DCMAKE_BUILD_TYPE=${build_type}" "-DCMAKE_CXX_COMPILER=${cxx}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  run_step("build the consumer project" ${CMAKE_COMMAND} --build "${build}" -j2)

  # The driver: exit 0 and the expected contact count.
  if(NOT EXISTS "${build}/driver")
    message(FATAL_ERROR "${CHECK_NAME}: the consumer build produced no ${build}/driver")
  endif()
  run_step("run the driver" "${build}/driver")
  if(NOT step_output MATCHES "contacts: 1\n")
    message(FATAL_ERROR "${CHECK_NAME}: the driver did not print 'contacts: 1'; it printed:\n${step_output}")
  endif()
  message(STATUS "driver output:\n${step_output}")

  # The toolkit driver (nscd::driver): the command line reaches its Config.
  run_step("run the toolkit driver" "${build}/toolkit_driver" --n 7 --name installed)
  if(NOT step_output MATCHES "toolkit_driver: n = 7, name = installed")
    message(FATAL_ERROR "${CHECK_NAME}: the toolkit driver printed:\n${step_output}")
  endif()
endfunction()
