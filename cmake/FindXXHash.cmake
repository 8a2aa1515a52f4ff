# FindXXHash: Debian's libxxhash-dev ships no CMake config. Provides XXHash::XXHash.
include(FibermoldFindLibrary)
fibermold_find_library(XXHash HEADER xxhash.h LIBRARY xxhash)
