# ctest install.consumer: installs the build tree into a fresh prefix, configures,
# builds and runs the consumer project (verification/install/consumer) against
# it with find_package(hofem), and checks the numbers it prints (a volume and a
# convergence rate, verification/install/consumer/main.cpp).
#   cmake -DBUILD=<hofem build dir> -DCONSUMER=<consumer source> -DWORK=<scratch dir>
#         -DCXX=<C++ compiler> -DC=<C compiler> -P TestInstallConsumer.cmake
file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install.consumer: ${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${prefix}")
# What a consumer relies on, named so that a missing piece says which.
foreach(f lib/cmake/hofem/hofemConfig.cmake lib/cmake/hofem/hofemConfigVersion.cmake
          lib/cmake/hofem/hofemTargets.cmake lib/cmake/hofem/HofemLibraryDependencies.cmake
          include/hofem/mesh/box_mesh.hpp include/hofem/quadrature/rule_library.hpp lib/libhofem_mesh.a)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "install.consumer: ${prefix}/${f} was not installed")
  endif()
endforeach()
run("configuring the consumer" ${CMAKE_COMMAND} -S "${CONSUMER}" -B "${WORK}/build"
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_COMPILER=${CXX}" "-DCMAKE_C_COMPILER=${C}")
run("building the consumer" ${CMAKE_COMMAND} --build "${WORK}/build" -j2)
run("running the consumer" "${WORK}/build/consumer")
message(STATUS "${out}")
# The unit cube's volume is exactly 1. The mesh's vertices (multiples of 0.5) make
# every det J exact; the rule's weights sum to 1/6 to within a few ulps and the
# ~48 products add up with rounding ~1e-15, so 1 +- 1e-11 passes and any wrong
# weight, Jacobian or element count (errors >= 1e-3) fails.
string(REGEX MATCH "unit cube volume ([^\n]+)" _ "${out}")
set(volume "${CMAKE_MATCH_1}")
if(NOT volume MATCHES "^(1|1\\.00000000000[0-9]*|0\\.99999999999[0-9]*)$")
  message(FATAL_ERROR "install.consumer: volume '${volume}', expected 1 to within 1e-11")
endif()
# The manufactured solution through the installed core: Tet10 between n = 4 and 8
# converges in L2 at the asymptotic rate p + 1 = 3; this pair, pre-asymptotic,
# measures 3.07 (reports/convergence.csv), so 3 +- 0.2 passes, while a wrong basis,
# rule or solve (P1 at the same sizes gives 1.74) fails.
string(REGEX MATCH "observed L2 rate ([0-9.eE+-]+)" _ "${out}")
set(rate "${CMAKE_MATCH_1}")
if(rate STREQUAL "" OR rate LESS 2.8 OR rate GREATER 3.2)
  message(FATAL_ERROR "install.consumer: L2 rate '${rate}', expected 3 +- 0.2")
endif()
