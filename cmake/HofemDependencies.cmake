# Finds every dependency hofem uses and turns each into an imported target.
# All come from Debian packages (scripts/install-deps installs them); a missing one
# stops configuration with the name of the Debian package that provides it.

include(HofemRequire)

find_package(Eigen3 3.4 QUIET NO_MODULE)
hofem_require(Eigen3_FOUND "Eigen 3.4" "libeigen3-dev")

find_package(fmt QUIET)
hofem_require(fmt_FOUND "fmt" "libfmt-dev")

find_package(nlohmann_json 3.10 QUIET)
hofem_require(nlohmann_json_FOUND "nlohmann-json" "nlohmann-json3-dev")

find_package(CLI11 QUIET)
hofem_require(CLI11_FOUND "CLI11" "libcli11-dev")

find_package(GTest QUIET)
hofem_require(GTest_FOUND "GoogleTest" "libgtest-dev")

find_package(benchmark QUIET)
hofem_require(benchmark_FOUND "Google Benchmark" "libbenchmark-dev")

# OpenMP (GCC's libgomp): element assembly runs colour by colour in parallel.
find_package(OpenMP QUIET COMPONENTS CXX)
hofem_require(OpenMP_CXX_FOUND "OpenMP for C++" "libgomp1 (part of g++)")

# MPI: Debian's hypre is an MPI build, so every program that uses it must call
# MPI_Init before HYPRE_Init (it then runs serially without mpirun).
find_package(MPI QUIET COMPONENTS C CXX)
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

add_library(hofem::suitesparse INTERFACE IMPORTED)
target_include_directories(hofem::suitesparse INTERFACE ${SUITESPARSE_INCLUDE_DIR})
target_link_libraries(hofem::suitesparse INTERFACE
  ${CHOLMOD_LIBRARY} ${UMFPACK_LIBRARY} ${AMD_LIBRARY} ${COLAMD_LIBRARY}
  ${SUITESPARSE_CONFIG_LIBRARY} ${OPENBLAS_LIBRARY})

# GLPK 5.0: the simplex solver of the LP quadrature simplification (Longva et al. 2020 §4.4).
find_path(GLPK_INCLUDE_DIR glpk.h)
find_library(GLPK_LIBRARY glpk)
set(_glpk_ok FALSE)
if(GLPK_INCLUDE_DIR AND GLPK_LIBRARY)
  set(_glpk_ok TRUE)
endif()
hofem_require(_glpk_ok "GLPK" "libglpk-dev")
add_library(hofem::glpk INTERFACE IMPORTED)
target_include_directories(hofem::glpk INTERFACE ${GLPK_INCLUDE_DIR})
target_link_libraries(hofem::glpk INTERFACE ${GLPK_LIBRARY})

# hypre 2.26 in Debian: no CMake config either.
find_path(HYPRE_INCLUDE_DIR HYPRE.h PATH_SUFFIXES hypre)
find_library(HYPRE_LIBRARY HYPRE)
set(_hypre_ok FALSE)
if(HYPRE_INCLUDE_DIR AND HYPRE_LIBRARY)
  set(_hypre_ok TRUE)
endif()
hofem_require(_hypre_ok "hypre" "libhypre-dev")
add_library(hofem::hypre INTERFACE IMPORTED)
target_include_directories(hofem::hypre INTERFACE ${HYPRE_INCLUDE_DIR})
# OMPI_SKIP_MPICXX: hypre's headers include mpi.h; the deprecated MPI C++ bindings
# would otherwise require MPI::MPI_CXX in every translation unit.
target_compile_definitions(hofem::hypre INTERFACE OMPI_SKIP_MPICXX=1)
target_link_libraries(hofem::hypre INTERFACE ${HYPRE_LIBRARY} MPI::MPI_C)

# numpy + matplotlib for the plots: Debian's interpreter, not whatever python3 is first on PATH.
set(HOFEM_PYTHON /usr/bin/python3 CACHE FILEPATH "Python interpreter with numpy and matplotlib")
