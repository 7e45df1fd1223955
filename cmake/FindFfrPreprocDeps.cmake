# Finds the preprocessor's native dependencies that ship no CMake package on Debian:
# gmsh (C++ API), CHOLMOD (SuiteSparse), METIS, ARPACK-ng. Defines imported targets
# ffr_dep::gmsh, ffr_dep::cholmod, ffr_dep::metis, ffr_dep::arpack, ffr_dep::lapack.

find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIBRARY gmsh REQUIRED)
add_library(ffr_dep::gmsh UNKNOWN IMPORTED)
set_target_properties(ffr_dep::gmsh PROPERTIES IMPORTED_LOCATION ${GMSH_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${GMSH_INCLUDE_DIR})

find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(ffr_dep::cholmod UNKNOWN IMPORTED)
set_target_properties(ffr_dep::cholmod PROPERTIES IMPORTED_LOCATION ${CHOLMOD_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${CHOLMOD_INCLUDE_DIR}
  INTERFACE_LINK_LIBRARIES ${SUITESPARSECONFIG_LIBRARY})

# METIS directly (CHOLMOD uses it too): the nodal ordering of the factorization's graph.
find_path(METIS_INCLUDE_DIR metis.h REQUIRED)
find_library(METIS_LIBRARY metis REQUIRED)
add_library(ffr_dep::metis UNKNOWN IMPORTED)
set_target_properties(ffr_dep::metis PROPERTIES IMPORTED_LOCATION ${METIS_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${METIS_INCLUDE_DIR})

find_library(ARPACK_LIBRARY arpack REQUIRED)
find_package(LAPACK REQUIRED)
add_library(ffr_dep::arpack UNKNOWN IMPORTED)
set_target_properties(ffr_dep::arpack PROPERTIES IMPORTED_LOCATION ${ARPACK_LIBRARY}
  INTERFACE_LINK_LIBRARIES "${LAPACK_LIBRARIES}")
add_library(ffr_dep::lapack INTERFACE IMPORTED)
set_target_properties(ffr_dep::lapack PROPERTIES INTERFACE_LINK_LIBRARIES "${LAPACK_LIBRARIES}")
