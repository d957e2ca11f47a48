# ctest verify.families: the ctest list of verification families
# (verification/unit/CMakeLists.txt, passed as EXPECTED) names every family of
# `hofem verify --list`, in its order, so no family goes untested by ctest.
#   cmake -DHOFEM=path/to/hofem -DEXPECTED="id id ..." -P TestVerifyFamilies.cmake
execute_process(COMMAND ${HOFEM} verify --list OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "hofem verify --list exited with ${rc}")
endif()
string(REGEX MATCHALL "[^\n]+" lines "${out}")
set(ids "")
foreach(line IN LISTS lines)
  string(REGEX MATCH "^[^ ]+" id "${line}")
  list(APPEND ids ${id})
endforeach()
list(JOIN ids " " ids)
if(NOT ids STREQUAL EXPECTED)
  message(FATAL_ERROR "hofem verify --list gives families\n  ${ids}\nctest has\n  ${EXPECTED}")
endif()
message(STATUS "verify.families: ${ids}")
