# Precompiled headers for the Qt, Qwt and nlohmann_json headers that the GUI, its widgets and
# the tests parse again in every translation unit. Measured on this project's 2-core machine
# (Release, GCC 12, ninja, clean build without ccache, 2026-11-29): compile CPU of the widgets
# 62 -> 29 s, the app's GUI library 193 -> 139 s, the core tests 340 -> 285 s, core 281 -> 258 s.
# The CLI has none: what CLI11 2.1 (header-only) costs is code generation for its global
# validator objects in every unit that includes it, not parsing, and a precompiled CLI11 in
# every CLI unit made the small ones slower (cancel.cpp 0.7 -> 9 s).
# A precompiled header changes no code: with STICKSLIP_PCH=OFF (or when the compiler cannot
# use the .gch) the same headers are read as text.
option(STICKSLIP_PCH "Precompile the heavy third-party headers (Qt, Qwt, nlohmann_json, Eigen)" ON)

# ccache caches a unit built with a precompiled header only with this sloppiness (ccache
# manual, "Precompiled headers"); the launcher sets it for these builds only.
if(STICKSLIP_PCH AND NOT STICKSLIP_FUZZ AND CMAKE_CXX_COMPILER_LAUNCHER)
  list(GET CMAKE_CXX_COMPILER_LAUNCHER 0 _stickslip_launcher)
  get_filename_component(_stickslip_launcher "${_stickslip_launcher}" NAME)
  if(_stickslip_launcher STREQUAL "ccache")
    set(CMAKE_CXX_COMPILER_LAUNCHER "${CMAKE_COMMAND};-E;env;CCACHE_SLOPPINESS=pch_defines,time_macros;${CMAKE_CXX_COMPILER_LAUNCHER}")
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      add_compile_options(-fpch-preprocess)
    endif()
  endif()
endif()

# stickslip_pch(target header...): `target` gets its own precompiled header of these headers.
function(stickslip_pch target)
  if(STICKSLIP_PCH AND NOT STICKSLIP_FUZZ)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()

# stickslip_pch_shared(target group header...): the first target of `group` builds the
# precompiled header, the others reuse it (one .gch for many small executables, e.g. the
# tests, whose sources include their own moc output). A group's targets must be compiled with
# the same flags and with the same definitions of any macro the headers read (GCC ignores a .gch
# that does not match and reads the headers as text: slower, never wrong).
function(stickslip_pch_shared target group)
  if(NOT STICKSLIP_PCH OR STICKSLIP_FUZZ)
    return()
  endif()
  string(MAKE_C_IDENTIFIER "stickslip_pch_${group}" key)
  get_property(owner GLOBAL PROPERTY ${key})
  if(owner)
    target_precompile_headers(${target} REUSE_FROM ${owner})
  else()
    set_property(GLOBAL PROPERTY ${key} ${target})
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
  # The tests include their moc output (`#include "tst_x.moc"`), so AUTOMOC's
  # mocs_compilation.cpp is empty; with the precompiled header it would still load the whole
  # .gch: 2.5 s of compile against 0.07 s without (2026-12-05), for each of ~70 tests. A
  # library's non-empty one keeps it (the GUI library's: 8.7 s with, 11.6 s without).
  get_target_property(automoc ${target} AUTOMOC)
  if(automoc)
    set_source_files_properties("${CMAKE_CURRENT_BINARY_DIR}/${target}_autogen/mocs_compilation.cpp"
                                PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
  endif()
endfunction()
