# nscd_add_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One static library per src/ folder, target nscd_<name>, alias nscd::<name>, exported as
# nscd::<name>. Dependencies between modules are written here, one way only.
function(nscd_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(nscd_${name} STATIC ${ARG_SOURCES})
  add_library(nscd::${name} ALIAS nscd_${name})
  set_target_properties(nscd_${name} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME nscd_${name})
  target_include_directories(nscd_${name} PUBLIC
    $<BUILD_INTERFACE:${NSCD_BUILD_INCLUDE}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(nscd_${name} PUBLIC cxx_std_20)
  nscd_warnings(nscd_${name})
  target_link_libraries(nscd_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  install(TARGETS nscd_${name} EXPORT nscdTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
endfunction()

function(nscd_warnings target)
  # -Wno-restrict: GCC 12 false positive on std::string concatenation (GCC bug 105651)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
endfunction()
