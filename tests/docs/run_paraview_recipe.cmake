# tests/docs/run_paraview_recipe.cmake — docs/output.md's ParaView recipe, run by
# contrib/paraview/recipe.py under `xvfb-run -a pvbatch` on a ballast run's VTK output (test
# paraview_recipe, label docs). Says "ParaView is not installed: skipped" without pvbatch or
# xvfb-run, and "ParaView's Python modules are missing: skipped" (the
# test's SKIP_REGULAR_EXPRESSION) when they cannot be imported (contrib/paraview/README.md: Debian's python3-paraview, unpacked; give its folder
# with -DNSCD_PARAVIEW_PYTHONPATH=...).
#   cmake -DRECIPE=... -DDIR=... -DPNG=... [-DPYTHONPATH=...] -P run_paraview_recipe.cmake
# pvbatch and xvfb-run are looked for now, not at configure time: installing ParaView later is enough
find_program(PVBATCH pvbatch)
find_program(XVFB_RUN xvfb-run)
if(NOT PVBATCH OR NOT XVFB_RUN)
  message(FATAL_ERROR "ParaView is not installed: skipped (pvbatch: ${PVBATCH}, xvfb-run: ${XVFB_RUN}; Debian: paraview xvfb)")
endif()
if(PYTHONPATH)
  set(ENV{PYTHONPATH} "${PYTHONPATH}")
endif()
foreach(attempt 1 2 3)  # xvfb-run -a can find the previous Xvfb still shutting down (status 134)
  execute_process(COMMAND ${XVFB_RUN} -a ${PVBATCH} "${RECIPE}" "${DIR}" -o "${PNG}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc EQUAL 134)
    break()
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E sleep 2)
endforeach()
if("${out}${err}" MATCHES "Python modules are missing")
  message(FATAL_ERROR "ParaView's Python modules are missing: skipped\n${err}")
endif()
if(NOT rc EQUAL 0 OR NOT out MATCHES "recipe: ok" OR NOT EXISTS "${PNG}")
  message(FATAL_ERROR "the ParaView recipe failed (status ${rc}):\n${out}\n${err}")
endif()
message(STATUS "${out}")
