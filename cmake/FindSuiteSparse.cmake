# FindSuiteSparse.cmake — finds the parts of SuiteSparse nscd uses (Debian 12 ships
# libsuitesparse-dev 5.12 without a CMake package configuration).
#
# Components: KLU (with AMD, COLAMD, BTF and SuiteSparse_config, which it needs), UMFPACK,
# CHOLMOD. With no COMPONENTS, KLU is looked for.
#
# Defines, for each component X found:  SuiteSparse::X (imported target), SuiteSparse_X_FOUND;
# and SuiteSparse_FOUND, SuiteSparse_INCLUDE_DIR, SuiteSparse_VERSION.
include(FindPackageHandleStandardArgs)

find_path(SuiteSparse_INCLUDE_DIR SuiteSparse_config.h PATH_SUFFIXES suitesparse)
if(SuiteSparse_INCLUDE_DIR AND EXISTS "${SuiteSparse_INCLUDE_DIR}/SuiteSparse_config.h")
  file(STRINGS "${SuiteSparse_INCLUDE_DIR}/SuiteSparse_config.h" _ss_lines
    REGEX "#define SUITESPARSE_(MAIN|SUB)_VERSION[ \t]+[0-9]+")
  string(REGEX REPLACE ".*MAIN_VERSION[ \t]+([0-9]+).*" "\\1" _ss_major "${_ss_lines}")
  string(REGEX REPLACE ".*SUB_VERSION[ \t]+([0-9]+).*" "\\1" _ss_minor "${_ss_lines}")
  set(SuiteSparse_VERSION "${_ss_major}.${_ss_minor}")
endif()

# _nscd_ss_lib(<target name> <library name> <header> <dependencies...>)
function(_nscd_ss_lib name lib header)
  find_library(SuiteSparse_${name}_LIBRARY NAMES ${lib})
  find_path(SuiteSparse_${name}_HEADER_DIR ${header} PATH_SUFFIXES suitesparse)
  mark_as_advanced(SuiteSparse_${name}_LIBRARY SuiteSparse_${name}_HEADER_DIR)
  if(SuiteSparse_${name}_LIBRARY AND SuiteSparse_${name}_HEADER_DIR)
    set(SuiteSparse_${name}_FOUND TRUE PARENT_SCOPE)
    if(NOT TARGET SuiteSparse::${name})
      add_library(SuiteSparse::${name} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${name} PROPERTIES
        IMPORTED_LOCATION "${SuiteSparse_${name}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_${name}_HEADER_DIR}")
      if(ARGN)
        set_property(TARGET SuiteSparse::${name} APPEND PROPERTY INTERFACE_LINK_LIBRARIES ${ARGN})
      endif()
    endif()
  else()
    set(SuiteSparse_${name}_FOUND FALSE PARENT_SCOPE)
  endif()
endfunction()

if(NOT SuiteSparse_FIND_COMPONENTS)
  set(SuiteSparse_FIND_COMPONENTS KLU)
endif()

_nscd_ss_lib(config suitesparseconfig SuiteSparse_config.h)
if(SuiteSparse_config_FOUND)
  _nscd_ss_lib(AMD amd amd.h SuiteSparse::config)
  _nscd_ss_lib(COLAMD colamd colamd.h SuiteSparse::config)
  _nscd_ss_lib(BTF btf btf.h)
  if(SuiteSparse_AMD_FOUND AND SuiteSparse_COLAMD_FOUND AND SuiteSparse_BTF_FOUND)
    _nscd_ss_lib(KLU klu klu.h SuiteSparse::AMD SuiteSparse::COLAMD SuiteSparse::BTF SuiteSparse::config)
  endif()
  if("UMFPACK" IN_LIST SuiteSparse_FIND_COMPONENTS OR "CHOLMOD" IN_LIST SuiteSparse_FIND_COMPONENTS)
    _nscd_ss_lib(CHOLMOD cholmod cholmod.h SuiteSparse::AMD SuiteSparse::COLAMD SuiteSparse::config)
    if(SuiteSparse_CHOLMOD_FOUND)
      _nscd_ss_lib(UMFPACK umfpack umfpack.h SuiteSparse::CHOLMOD SuiteSparse::AMD SuiteSparse::config)
    endif()
  endif()
endif()

find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS SuiteSparse_INCLUDE_DIR
  VERSION_VAR SuiteSparse_VERSION
  HANDLE_COMPONENTS)
mark_as_advanced(SuiteSparse_INCLUDE_DIR)
