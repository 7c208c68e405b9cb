message(STATUS "install check: not written yet")
