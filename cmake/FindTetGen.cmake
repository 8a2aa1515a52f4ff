# FindTetGen: Debian's libtet1.5-dev ships no CMake config.
# Provides TetGen::TetGen with TETLIBRARY defined (without it tetgen.h hides the library API and
# errors call exit() instead of throwing).
include(FibermoldFindLibrary)
fibermold_find_library(TetGen HEADER tetgen.h LIBRARY tet tetgen DEFINITIONS TETLIBRARY)
