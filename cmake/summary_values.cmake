# Helpers for ctest scripts (cmake -P) that read a driver's summary.txt ("key = value" lines).
#   summary_value(FILE KEY OUT)   the value of KEY; a FATAL_ERROR naming the file if it is absent
#   whole_degrees(TEXT OUT)       the whole part of a decimal text (math() has integers only):
#                                 "-3.7" -> -3, "27.2" -> 27, "-2.5e-05" -> 0 (17-digit summaries
#                                 write small values with an exponent)
function(summary_value file key out)
  file(STRINGS ${file} lines REGEX "^${key} = ")
  if(NOT lines)
    message(FATAL_ERROR "${file}: no '${key} = ' line")
  endif()
  string(REGEX REPLACE "^${key} = " "" v "${lines}")
  set(${out} ${v} PARENT_SCOPE)
endfunction()

function(whole_degrees text out)
  if(text MATCHES "e-")
    set(text 0)
  endif()
  string(REGEX REPLACE "\\..*" "" w "${text}")
  if(w STREQUAL "-" OR w STREQUAL "")
    set(w 0)
  endif()
  set(${out} ${w} PARENT_SCOPE)
endfunction()
