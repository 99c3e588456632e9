# FindQwt: Qwt 6 for Qt 5 (Debian's libqwt-qt5-dev ships no CMake config, and its
# pkg-config file Qt5Qwt6.pc needs libqt5opengl5-dev). Defines the imported target Qwt::Qwt
# and Qwt_FOUND, Qwt_VERSION, Qwt_INCLUDE_DIR, Qwt_LIBRARY.
find_path(Qwt_INCLUDE_DIR NAMES qwt_plot.h
          PATHS /usr/include /usr/local/include
          PATH_SUFFIXES qwt qwt-qt5 qt5/qwt)
find_library(Qwt_LIBRARY NAMES qwt-qt5 qwt6-qt5 qwt
             PATHS /usr/lib /usr/local/lib)

if(Qwt_INCLUDE_DIR AND EXISTS "${Qwt_INCLUDE_DIR}/qwt_global.h")
  file(STRINGS "${Qwt_INCLUDE_DIR}/qwt_global.h" _qwt_version_line
       REGEX "^#define[ \t]+QWT_VERSION_STR[ \t]+\"[0-9.]+\"")
  string(REGEX REPLACE ".*\"([0-9.]+)\".*" "\\1" Qwt_VERSION "${_qwt_version_line}")
  unset(_qwt_version_line)
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Qwt
  REQUIRED_VARS Qwt_LIBRARY Qwt_INCLUDE_DIR
  VERSION_VAR Qwt_VERSION)

# Qwt 6.1.4's qwt_series_store.h declares `~QwtSeriesStore<T>()`, which C++20 forbids
# (DR 2237; GCC 11+ rejects it). Headers are included with quotes from their own directory,
# so a single replacement header is not enough: configure a copy of the whole header
# directory into the build tree with that one line fixed, and use the copy.
set(Qwt_USE_INCLUDE_DIR "${Qwt_INCLUDE_DIR}")
if(Qwt_FOUND AND EXISTS "${Qwt_INCLUDE_DIR}/qwt_series_store.h")
  file(READ "${Qwt_INCLUDE_DIR}/qwt_series_store.h" _qwt_store)
  if(_qwt_store MATCHES "~QwtSeriesStore<T>\\(\\)")
    set(_qwt_compat "${CMAKE_BINARY_DIR}/qwt-cxx20/qwt")
    file(GLOB _qwt_headers "${Qwt_INCLUDE_DIR}/*.h" "${Qwt_INCLUDE_DIR}/Qwt*")
    file(COPY ${_qwt_headers} DESTINATION "${_qwt_compat}")
    string(REPLACE "~QwtSeriesStore<T>()" "~QwtSeriesStore()" _qwt_store "${_qwt_store}")
    string(REPLACE "explicit QwtSeriesStore<T>()" "explicit QwtSeriesStore()" _qwt_store "${_qwt_store}")
    file(WRITE "${_qwt_compat}/qwt_series_store.h" "${_qwt_store}")
    set(Qwt_USE_INCLUDE_DIR "${_qwt_compat}")
    unset(_qwt_headers)
    unset(_qwt_compat)
  endif()
  unset(_qwt_store)
endif()

if(Qwt_FOUND AND NOT TARGET Qwt::Qwt)
  find_package(Qt5 5.15 REQUIRED COMPONENTS Core Gui Widgets Svg PrintSupport)
  add_library(Qwt::Qwt UNKNOWN IMPORTED)
  set_target_properties(Qwt::Qwt PROPERTIES
    IMPORTED_LOCATION "${Qwt_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${Qwt_USE_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "Qt5::Widgets;Qt5::Svg;Qt5::PrintSupport")
endif()
mark_as_advanced(Qwt_INCLUDE_DIR Qwt_LIBRARY)
