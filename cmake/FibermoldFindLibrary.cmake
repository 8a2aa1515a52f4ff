# fibermold_find_library(NAME HEADER <file> LIBRARY <names...> [PATH_SUFFIXES <dirs...>]
#                        [ALSO_LINK <libraries...>] [DEFINITIONS <definitions...>])
# What a Find module does for a Debian package that ships no CMake config: finds the header and the
# library (and any library it needs beside it), reports as find_package does (NAME_FOUND, the
# REQUIRED message), and provides the imported target NAME::NAME with the header's folder, the
# libraries and the compile definitions its users need. A macro: the results stay in the caller's scope.
include(FindPackageHandleStandardArgs)
macro(fibermold_find_library name)
  cmake_parse_arguments(_fl "" "HEADER" "LIBRARY;PATH_SUFFIXES;ALSO_LINK;DEFINITIONS" ${ARGN})
  find_path(${name}_INCLUDE_DIR ${_fl_HEADER} PATH_SUFFIXES ${_fl_PATH_SUFFIXES})
  find_library(${name}_LIBRARY NAMES ${_fl_LIBRARY})
  set(_fl_required ${name}_LIBRARY ${name}_INCLUDE_DIR)
  set(_fl_links "")
  foreach(_fl_also IN ITEMS ${_fl_ALSO_LINK})
    find_library(${name}_${_fl_also}_LIBRARY NAMES ${_fl_also})
    list(APPEND _fl_required ${name}_${_fl_also}_LIBRARY)
    list(APPEND _fl_links "${${name}_${_fl_also}_LIBRARY}")
  endforeach()
  find_package_handle_standard_args(${name} REQUIRED_VARS ${_fl_required})
  if(${name}_FOUND AND NOT TARGET ${name}::${name})
    add_library(${name}::${name} UNKNOWN IMPORTED)
    set_target_properties(${name}::${name} PROPERTIES
      IMPORTED_LOCATION "${${name}_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${${name}_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${_fl_links}"
      INTERFACE_COMPILE_DEFINITIONS "${_fl_DEFINITIONS}")
  endif()
  mark_as_advanced(${_fl_required})
endmacro()
