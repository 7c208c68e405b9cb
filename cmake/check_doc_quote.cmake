# cmake -DSOURCE=<file> -DDOC=<markdown> -DMARKER=<text> -P check_doc_quote.cmake
# The first ```cpp block of DOC after the line that holds MARKER must equal SOURCE, line for
# line: a document that quotes a source file whole cannot drift from it.
file(READ "${SOURCE}" src)
file(READ "${DOC}" doc)
string(FIND "${doc}" "${MARKER}" at)
if(at LESS 0)
  message(FATAL_ERROR "${DOC} does not mention ${MARKER}")
endif()
string(SUBSTRING "${doc}" ${at} -1 doc)
string(FIND "${doc}" "```cpp\n" open)
if(open LESS 0)
  message(FATAL_ERROR "${DOC}: no ```cpp block after ${MARKER}")
endif()
math(EXPR open "${open} + 7")
string(SUBSTRING "${doc}" ${open} -1 doc)
string(FIND "${doc}" "```\n" close)
string(SUBSTRING "${doc}" 0 ${close} quoted)
if(NOT quoted STREQUAL src)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/quoted.txt" "${quoted}")
  message(FATAL_ERROR "the ```cpp block of ${DOC} after ${MARKER} differs from ${SOURCE} (it was written to "
    "${CMAKE_CURRENT_BINARY_DIR}/quoted.txt): copy the file into the document again")
endif()
message(STATUS "${DOC} quotes ${SOURCE} exactly")
