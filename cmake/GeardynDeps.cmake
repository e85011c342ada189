# Every dependency is a Debian 12 package installed by scripts/install-deps.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Threads REQUIRED)
# zlib (zlib1g-dev): compressed binary VTU output.
find_package(ZLIB REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(TOMLPP REQUIRED IMPORTED_TARGET tomlplusplus)
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)

# Spectra is header-only (/usr/include/Spectra).
find_path(SPECTRA_INCLUDE_DIR Spectra/SymEigsShiftSolver.h REQUIRED)
add_library(geardyn_spectra INTERFACE)
target_include_directories(geardyn_spectra SYSTEM INTERFACE ${SPECTRA_INCLUDE_DIR})
target_link_libraries(geardyn_spectra INTERFACE Eigen3::Eigen)

# SuiteSparse (CHOLMOD, UMFPACK) used through Eigen's CholmodSupport / UmfPackSupport.
find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(UMFPACK_LIBRARY umfpack REQUIRED)
find_library(AMD_LIBRARY amd REQUIRED)
find_library(COLAMD_LIBRARY colamd REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(geardyn_suitesparse INTERFACE)
target_include_directories(geardyn_suitesparse SYSTEM INTERFACE ${SUITESPARSE_INCLUDE_DIR})
target_link_libraries(geardyn_suitesparse INTERFACE ${UMFPACK_LIBRARY} ${CHOLMOD_LIBRARY}
  ${AMD_LIBRARY} ${COLAMD_LIBRARY} ${SUITESPARSECONFIG_LIBRARY} Eigen3::Eigen)

# Gmsh API (libgmsh-dev): mesh reading and the parametric sector generator.
find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIBRARY gmsh REQUIRED)
add_library(geardyn_gmsh INTERFACE)
target_include_directories(geardyn_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_link_libraries(geardyn_gmsh INTERFACE ${GMSH_LIBRARY})

# HDF5 C library (libhdf5-dev, serial): reduced components and large result fields.
set(HDF5_PREFER_PARALLEL OFF)
find_package(HDF5 REQUIRED COMPONENTS C)
add_library(geardyn_hdf5 INTERFACE)
target_include_directories(geardyn_hdf5 SYSTEM INTERFACE ${HDF5_C_INCLUDE_DIRS})
target_link_libraries(geardyn_hdf5 INTERFACE ${HDF5_C_LIBRARIES})
target_compile_definitions(geardyn_hdf5 INTERFACE ${HDF5_C_DEFINITIONS})

find_package(GTest REQUIRED)
if(GEARDYN_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
