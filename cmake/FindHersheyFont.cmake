# FindHersheyFont: Debian's libhersheyfont-dev ships no CMake config. Provides HersheyFont::HersheyFont
# (the C library that loads a Hershey .jhf font into glyph strokes; the fonts are hershey-fonts-data's).
include(FibermoldFindLibrary)
fibermold_find_library(HersheyFont HEADER hersheyfont.h LIBRARY hersheyfont)
