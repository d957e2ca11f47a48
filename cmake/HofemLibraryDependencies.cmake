# The dependencies hofem's core libraries link, each turned into an imported
# target. One home for both users: the project (through HofemDependencies.cmake)
# and an installed hofem (hofemConfig.cmake includes this file from
# <prefix>/lib/cmake/hofem, so find_package(hofem) re-finds what the exported
# targets name). Off Debian, point CMake at a library with CMAKE_PREFIX_PATH or
# the cache variables below (SUITESPARSE_INCLUDE_DIR, CHOLMOD_LIBRARY, ...).
# A missing one stops configuration with the Debian package that provides it.

include(${CMAKE_CURRENT_LIST_DIR}/HofemRequire.cmake)

find_package(Eigen3 3.4 QUIET NO_MODULE)
hofem_require(Eigen3_FOUND "Eigen 3.4" "libeigen3-dev")

find_package(fmt QUIET)
hofem_require(fmt_FOUND "fmt" "libfmt-dev")

find_package(nlohmann_json 3.10 QUIET)
hofem_require(nlohmann_json_FOUND "nlohmann-json" "nlohmann-json3-dev")

# zlib: compressed binary .vtu output (io/vtu_appended.cpp, vtkZLibDataCompressor
# layout). CMake's FindZLIB gives the imported target ZLIB::ZLIB.
find_package(ZLIB QUIET)
hofem_require(ZLIB_FOUND "zlib" "zlib1g-dev")

# OpenMP (GCC's libgomp): element assembly runs colour by colour in parallel.
find_package(OpenMP QUIET COMPONENTS CXX)
hofem_require(OpenMP_CXX_FOUND "OpenMP for C++" "libgomp1 (part of g++)")

# MPI: Debian's hypre is an MPI build, so every program that uses it must call
# MPI_Init before HYPRE_Init (it then runs serially without mpirun). Only the C
# interface is linked (hofem::hypre below); FindMPI needs the C language enabled.
get_property(_hofem_languages GLOBAL PROPERTY ENABLED_LANGUAGES)
if(NOT "C" IN_LIST _hofem_languages)
  enable_language(C)
endif()
find_package(MPI QUIET COMPONENTS C)
hofem_require(MPI_FOUND "MPI (Open MPI)" "libopenmpi-dev")

# SuiteSparse 5.x in Debian ships no CMake config: find headers and libraries directly.
find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(CHOLMOD_LIBRARY cholmod)
find_library(UMFPACK_LIBRARY umfpack)
find_library(SUITESPARSE_CONFIG_LIBRARY suitesparseconfig)
find_library(AMD_LIBRARY amd)
find_library(COLAMD_LIBRARY colamd)
set(_ss_ok FALSE)
if(SUITESPARSE_INCLUDE_DIR AND CHOLMOD_LIBRARY AND UMFPACK_LIBRARY AND SUITESPARSE_CONFIG_LIBRARY)
  set(_ss_ok TRUE)
endif()
hofem_require(_ss_ok "SuiteSparse (CHOLMOD, UMFPACK)" "libsuitesparse-dev")

# CHOLMOD factors ~10x faster with OpenBLAS than with the reference BLAS (see
# shared/machine.md); require it so the benchmark figures mean something.
find_library(OPENBLAS_LIBRARY NAMES openblas)
hofem_require(OPENBLAS_LIBRARY "OpenBLAS" "libopenblas-dev")

# GLPK 5.0: the simplex solver of the LP quadrature simplification (Longva et al. 2020 §4.4).
find_path(GLPK_INCLUDE_DIR glpk.h)
find_library(GLPK_LIBRARY glpk)
set(_glpk_ok FALSE)
if(GLPK_INCLUDE_DIR AND GLPK_LIBRARY)
  set(_glpk_ok TRUE)
endif()
hofem_require(_glpk_ok "GLPK" "libglpk-dev")

# hypre 2.26 in Debian: no CMake config either.
find_path(HYPRE_INCLUDE_DIR HYPRE.h PATH_SUFFIXES hypre)
find_library(HYPRE_LIBRARY HYPRE)
set(_hypre_ok FALSE)
if(HYPRE_INCLUDE_DIR AND HYPRE_LIBRARY)
  set(_hypre_ok TRUE)
endif()
hofem_require(_hypre_ok "hypre" "libhypre-dev")

# The imported targets; a consumer may call find_package(hofem) more than once.
if(NOT TARGET hofem::suitesparse)
  add_library(hofem::suitesparse INTERFACE IMPORTED)
  target_include_directories(hofem::suitesparse INTERFACE ${SUITESPARSE_INCLUDE_DIR})
  target_link_libraries(hofem::suitesparse INTERFACE
    ${CHOLMOD_LIBRARY} ${UMFPACK_LIBRARY} ${AMD_LIBRARY} ${COLAMD_LIBRARY}
    ${SUITESPARSE_CONFIG_LIBRARY} ${OPENBLAS_LIBRARY})
endif()
if(NOT TARGET hofem::glpk)
  add_library(hofem::glpk INTERFACE IMPORTED)
  target_include_directories(hofem::glpk INTERFACE ${GLPK_INCLUDE_DIR})
  target_link_libraries(hofem::glpk INTERFACE ${GLPK_LIBRARY})
endif()
if(NOT TARGET hofem::hypre)
  add_library(hofem::hypre INTERFACE IMPORTED)
  target_include_directories(hofem::hypre INTERFACE ${HYPRE_INCLUDE_DIR})
  # OMPI_SKIP_MPICXX: hypre's headers include mpi.h; the deprecated MPI C++ bindings
  # would otherwise require MPI::MPI_CXX in every translation unit.
  target_compile_definitions(hofem::hypre INTERFACE OMPI_SKIP_MPICXX=1)
  target_link_libraries(hofem::hypre INTERFACE ${HYPRE_LIBRARY} MPI::MPI_C)
endif()
