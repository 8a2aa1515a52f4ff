# Every dependency comes from Debian 12's packages (scripts/setup installs them).
# Order matters: config packages first, CGAL last (its own FindEigen3/FindTBB would shadow the
# config packages' targets).
find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED CONFIG)
find_package(TBB REQUIRED CONFIG)
find_package(assimp REQUIRED CONFIG)
find_package(tomlplusplus REQUIRED CONFIG)
find_package(CLI11 REQUIRED CONFIG)
find_package(fmt REQUIRED CONFIG)
find_package(spdlog REQUIRED CONFIG)
find_package(nlohmann_json REQUIRED CONFIG)
find_package(nanoflann REQUIRED CONFIG)
find_package(GTest REQUIRED CONFIG)
find_package(benchmark REQUIRED CONFIG)
find_package(TetGen REQUIRED)
find_package(CHOLMOD REQUIRED)
find_package(XXHash REQUIRED)
find_package(HersheyFont REQUIRED)

# OpenVDB: Debian ships only a find module, outside CMake's default module path.
list(APPEND CMAKE_MODULE_PATH /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)

find_package(CGAL REQUIRED)
find_package(Boost 1.74 REQUIRED) # headers only: Boost.Graph's Cuthill–McKee ordering (sim/band_ordering.cpp)
