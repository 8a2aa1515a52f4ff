# FindHersheyFont: Debian's libhersheyfont-dev ships no CMake config. Provides HersheyFont::HersheyFont
# (the C library that loads a Hershey .jhf font into glyph strokes; the fonts are hershey-fonts-data's).
find_path(HersheyFont_INCLUDE_DIR hersheyfont.h)
find_library(HersheyFont_LIBRARY NAMES hersheyfont)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(HersheyFont REQUIRED_VARS HersheyFont_LIBRARY HersheyFont_INCLUDE_DIR)
if(HersheyFont_FOUND AND NOT TARGET HersheyFont::HersheyFont)
  add_library(HersheyFont::HersheyFont UNKNOWN IMPORTED)
  set_target_properties(HersheyFont::HersheyFont PROPERTIES
    IMPORTED_LOCATION "${HersheyFont_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${HersheyFont_INCLUDE_DIR}")
endif()
mark_as_advanced(HersheyFont_INCLUDE_DIR HersheyFont_LIBRARY)
