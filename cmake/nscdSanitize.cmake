# cmake/nscdSanitize.cmake — the NSCD_SANITIZE option: build every nscd target (libraries,
# scenes, tests, validation, drivers, benchmarks) with GCC's or Clang's sanitizers.
#   -DNSCD_SANITIZE=OFF                (default) no sanitizer
#   -DNSCD_SANITIZE=address,undefined  AddressSanitizer (with LeakSanitizer) and UBSan
#   -DNSCD_SANITIZE=address | undefined  one of them
#   -DNSCD_SANITIZE=thread             ThreadSanitizer, alone and with Clang only: GCC's OpenMP
#                                      runtime is not instrumented, so TSan would report its own
#                                      barriers; Clang's libomp has the Archer tool for them
#                                      (tests/sanitize/run_tsan.cmake runs the threaded tests so)
# Compile: -fsanitize=<list> -fno-omit-frame-pointer, and -fno-sanitize-recover=undefined when
# UBSan is on (its first report ends the program, so a test cannot pass over it), and with GCC
# -Wno-maybe-uninitialized (below).
# Link: -fsanitize=<list>, also recorded on the exported libraries (nscd_add_module,
# nscd::scenes): a project linking an installed sanitized nscd links the runtimes without
# knowing. A sanitized build is for checking, not for runs: see docs/user-guide.md §1.1.
set(NSCD_SANITIZE "OFF" CACHE STRING
  "Sanitizers for every nscd target: OFF, a comma list of address, undefined (e.g. address,undefined), or thread")
set_property(CACHE NSCD_SANITIZE PROPERTY STRINGS "OFF" "address,undefined" "address" "undefined" "thread")

set(NSCD_SANITIZE_COMPILE_FLAGS "")
set(NSCD_SANITIZE_LINK_FLAGS "")
if(NOT NSCD_SANITIZE STREQUAL "" AND NOT NSCD_SANITIZE MATCHES "^(OFF|Off|off|NO|no|FALSE|false|0)$")
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "^(GNU|Clang)$")
    message(FATAL_ERROR "NSCD_SANITIZE=${NSCD_SANITIZE} needs GCC or Clang; the compiler is ${CMAKE_CXX_COMPILER_ID}")
  endif()
  string(REPLACE "," ";" _nscd_sanitizers "${NSCD_SANITIZE}")
  foreach(s IN LISTS _nscd_sanitizers)
    if(NOT s MATCHES "^(address|undefined|thread)$")
      message(FATAL_ERROR "NSCD_SANITIZE=${NSCD_SANITIZE}: unknown sanitizer '${s}' "
        "(use OFF, a comma list of address, undefined, e.g. -DNSCD_SANITIZE=address,undefined, or thread)")
    endif()
  endforeach()
  if("thread" IN_LIST _nscd_sanitizers)
    list(LENGTH _nscd_sanitizers _nscd_count)
    if(_nscd_count GREATER 1)
      message(FATAL_ERROR "NSCD_SANITIZE=${NSCD_SANITIZE}: thread cannot be combined with another sanitizer")
    endif()
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
      message(FATAL_ERROR "NSCD_SANITIZE=thread needs Clang (configure with CC=clang CXX=clang++): "
        "GCC's OpenMP runtime, libgomp, is not instrumented, so ThreadSanitizer reports its barriers as races")
    endif()
  endif()
  list(REMOVE_DUPLICATES _nscd_sanitizers)
  list(JOIN _nscd_sanitizers "," _nscd_sanitize_list)
  set(NSCD_SANITIZE_COMPILE_FLAGS -fsanitize=${_nscd_sanitize_list} -fno-omit-frame-pointer)
  if("undefined" IN_LIST _nscd_sanitizers)
    list(APPEND NSCD_SANITIZE_COMPILE_FLAGS -fno-sanitize-recover=undefined)
  endif()
  # GCC's manual warns that sanitizers raise false -Wmaybe-uninitialized warnings; GCC 12 gives
  # 14 of them inside libstdc++'s <regex> (std::function in regex_automaton.h) for the tests that
  # use std::regex. The normal build keeps that warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    list(APPEND NSCD_SANITIZE_COMPILE_FLAGS -Wno-maybe-uninitialized)
  endif()
  set(NSCD_SANITIZE_LINK_FLAGS -fsanitize=${_nscd_sanitize_list})
  add_compile_options(${NSCD_SANITIZE_COMPILE_FLAGS})
  add_link_options(${NSCD_SANITIZE_LINK_FLAGS})
  list(JOIN NSCD_SANITIZE_COMPILE_FLAGS " " _nscd_flags_text)
  message(STATUS "nscd: sanitizers ${_nscd_sanitize_list} (compile: ${_nscd_flags_text})")
else()
  message(STATUS "nscd: sanitizers OFF")
endif()
