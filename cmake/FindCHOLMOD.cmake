# FindCHOLMOD: SuiteSparse 5 in Debian ships no CMake config.
# Provides CHOLMOD::CHOLMOD; /usr/include/suitesparse goes on the include path because
# <Eigen/CholmodSupport> includes <cholmod.h>.
include(FibermoldFindLibrary)
fibermold_find_library(CHOLMOD HEADER cholmod.h PATH_SUFFIXES suitesparse LIBRARY cholmod ALSO_LINK suitesparseconfig)
