# Finds every dependency hofem uses and turns each into an imported target.
# All come from Debian packages (scripts/install-deps installs them); a missing one
# stops configuration with the name of the Debian package that provides it.
# The libraries' dependencies live in HofemLibraryDependencies.cmake (installed
# with hofemConfig.cmake, so consumers find the same ones); this file adds what
# only the project's programs and tests need.

include(HofemRequire)
include(HofemLibraryDependencies)

find_package(CLI11 QUIET)
hofem_require(CLI11_FOUND "CLI11" "libcli11-dev")

find_package(GTest QUIET)
hofem_require(GTest_FOUND "GoogleTest" "libgtest-dev")

find_package(benchmark QUIET)
hofem_require(benchmark_FOUND "Google Benchmark" "libbenchmark-dev")

# numpy + matplotlib for the plots: Debian's interpreter, not whatever python3 is first on PATH.
set(HOFEM_PYTHON /usr/bin/python3 CACHE FILEPATH "Python interpreter with numpy and matplotlib")

# sympy derives the material laws the verification suite compares core/material
# with (verification/symbolic/derive_material_laws.py, run at build time).
execute_process(COMMAND /usr/bin/python3 -c "import sympy" RESULT_VARIABLE HOFEM_SYMPY_STATUS OUTPUT_QUIET ERROR_QUIET)
if(HOFEM_SYMPY_STATUS EQUAL 0)
  set(HOFEM_SYMPY_FOUND TRUE)
endif()
hofem_require(HOFEM_SYMPY_FOUND "sympy (for /usr/bin/python3)" "python3-sympy")
